// The host's side of the ordered stream (see send_window.h).
#include "host/lib/stream/send_window.h"

#include <algorithm>  // std::max

#include "firmware/protocol/wire_codes.h"  // proto::kCmdSplineHeader

namespace host {

// Index of the in-flight command carrying seq (within 128 of base), or SIZE_MAX.
size_t SendWindow::index_of_seq(uint8_t seq) const {
  if (commands == nullptr) return SIZE_MAX;
  const uint8_t base_seq = static_cast<uint8_t>(first_seq + base);
  // The 8-bit wrap to a signed distance is the point (sequence numbers are modulo 256).
  // NOLINTNEXTLINE(bugprone-signed-char-misuse)
  const int delta = static_cast<int8_t>(static_cast<uint8_t>(seq - base_seq));
  const long index = static_cast<long>(base) + delta;
  if (index < 0 || index > static_cast<long>(commands->size())) return SIZE_MAX;
  return static_cast<size_t>(index);
}

// Execution progress. The executed frame is one the controller stored, so it lies between
// executed and the stored frontier base; its seq is read backwards from base, which is
// unambiguous however many frames ran since the previous status (counting forward from
// executed is not: more than 127 frames between two statuses read as "behind" and the job
// never completed).
void SendWindow::track_executed(uint8_t last_executed_seq) {
  if (base == 0) return;
  const uint8_t newest_stored = static_cast<uint8_t>(first_seq + base - 1);
  const size_t behind = static_cast<uint8_t>(newest_stored - last_executed_seq);
  if (behind >= base || behind >= 128) return;  // before this run's first command
  executed = std::max(executed, base - behind);
}

// Whether the controller has a spline slot for the #B at next: the newest *O or *? said
// how many were free after the frames before splines_known_at; every #B sent since took
// one. (A slot frees when its spline has run; the status polls see that.)
bool SendWindow::spline_room() const {
  if (splines_free == kSplineSlotsUnknown) return true;
  size_t taken = 0;
  for (size_t i = splines_known_at; i < next && i < commands->size(); ++i) {
    if (commands->at(i).letter == proto::kCmdSplineHeader) ++taken;
  }
  return splines_free > taken;
}

}  // namespace host
