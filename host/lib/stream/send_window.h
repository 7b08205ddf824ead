// The ordered stream of one Sender::run() on the host's side: which commands the controller
// stored (base), which went out (next), which ran (executed), and the flow control the
// controller's replies allow (window, busy, queue and spline room, the last seq_gap).
#ifndef HOST_LIB_STREAM_SEND_WINDOW_H
#define HOST_LIB_STREAM_SEND_WINDOW_H

#include <chrono>   // std::chrono
#include <cstddef>  // size_t
#include <cstdint>  // uint8_t, SIZE_MAX
#include <vector>   // std::vector

#include "host/lib/stream/command_source.h"  // CommandSource

namespace host {

struct SendWindow {
  // Index of the in-flight command carrying seq (within 128 of base), or SIZE_MAX.
  size_t index_of_seq(uint8_t seq) const;
  // The status's last_executed_seq: moves `executed` on (see the .cpp).
  void track_executed(uint8_t last_executed_seq);
  // Whether the controller has a spline slot for the #B at next.
  bool spline_room() const;

  CommandSource* commands = nullptr;
  uint8_t first_seq = 0;   // seq of commands[0]
  size_t base = 0;         // oldest command not yet acknowledged
  size_t next = 0;         // next command to (re)send
  size_t executed = 0;     // commands executed (count)
  size_t high_water = 0;   // one past the furthest command sent (one below it is a resend)
  bool busy_wait = false;  // after *E busy: send nothing new until an *O
  size_t frames = 1;       // frames in flight the controller allows (*I)
  size_t limit = 1;        // frames in flight allowed now: 1 after *E busy, grows per *O
  size_t queue_free = 1;   // controller queue room, from the newest *O or *?
  // Spline slots free after the ordered frames before splines_known_at (newest *O or *?).
  static constexpr size_t kSplineSlotsUnknown = SIZE_MAX;
  size_t splines_free = kSplineSlotsUnknown;
  size_t splines_known_at = 0;
  std::chrono::steady_clock::time_point oldest_sent;
  size_t last_gap_expected = SIZE_MAX;  // the seq_gap we went back for, and when
  std::chrono::steady_clock::time_point last_gap_at{};
};

}  // namespace host

#endif  // HOST_LIB_STREAM_SEND_WINDOW_H
