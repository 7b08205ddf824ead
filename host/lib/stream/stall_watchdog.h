// The sender's stall watchdog: a job stalls when nothing changed for the limit (acks,
// executions, the tool's position, the machine state) while nobody waits for the operator.
#ifndef HOST_LIB_STREAM_STALL_WATCHDOG_H
#define HOST_LIB_STREAM_STALL_WATCHDOG_H

#include <chrono>   // std::chrono
#include <cstddef>  // size_t
#include <cstdint>  // int32_t

#include "firmware/protocol/wire_codes.h"  // proto::MachineState

namespace host {

class StallWatchdog {
 public:
  using Clock = std::chrono::steady_clock;

  // What the watchdog compares from one look to the next.
  struct Seen {
    size_t acked = 0, executed = 0;
    int32_t x_um = 0, y_um = 0, z_um = 0;
    proto::MachineState state = proto::MachineState::kIdle;
  };

  // A new job starts at t.
  void start(Clock::time_point t) {
    seen_ = Seen();
    last_progress_ = t;
  }
  // True once nothing changed for `limit` (0: never); waiting for the operator is progress.
  bool stalled(const Seen& s, bool waits_for_operator, Clock::time_point t,
               std::chrono::milliseconds limit) {
    if (s.acked != seen_.acked || s.executed != seen_.executed || s.x_um != seen_.x_um ||
        s.y_um != seen_.y_um || s.z_um != seen_.z_um || s.state != seen_.state ||
        waits_for_operator) {
      seen_ = s;
      last_progress_ = t;
      return false;
    }
    return limit.count() > 0 && t - last_progress_ > limit;
  }

 private:
  Seen seen_;
  Clock::time_point last_progress_;
};

}  // namespace host

#endif  // HOST_LIB_STREAM_STALL_WATCHDOG_H
