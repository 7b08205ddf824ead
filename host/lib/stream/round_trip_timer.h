// The sender's retransmission timer: the round trip smoothed (1/8 gain) over frames
// acknowledged at their first sending (Karn's rule: a frame sent again, or held by the
// controller for room, says nothing about the link), and the time-out it gives.
#ifndef HOST_LIB_STREAM_ROUND_TRIP_TIMER_H
#define HOST_LIB_STREAM_ROUND_TRIP_TIMER_H

#include <algorithm>  // std::max
#include <chrono>     // std::chrono
#include <cstddef>    // size_t
#include <vector>     // std::vector

namespace host {

class RoundTripTimer {
 public:
  using Clock = std::chrono::steady_clock;

  // A new stream of `frames` frames (0: no samples at all, as for the zeroing frame).
  void start(size_t frames) {
    first_sent_.assign(frames, Clock::time_point{});
    resent_.assign(frames, false);
  }
  // Frame `index` went out at `t`; again: it gives no sample any more.
  void sent(size_t index, bool again, Clock::time_point t) {
    if (index >= first_sent_.size()) return;
    if (again)
      resent_[index] = true;
    else
      first_sent_[index] = t;
  }
  // Frame `index` was acknowledged at `t`.
  void acknowledged(size_t index, Clock::time_point t) {
    if (index >= first_sent_.size() || resent_[index]) return;
    const auto sample =
        std::chrono::duration_cast<std::chrono::milliseconds>(t - first_sent_[index]);
    srtt_ = (7 * srtt_ + sample) / 8;
  }
  std::chrono::milliseconds smoothed() const { return srtt_; }
  // Unacknowledged this long, a frame counts as lost.
  std::chrono::milliseconds timeout(std::chrono::milliseconds floor) const {
    return std::max(floor, 4 * srtt_);
  }

 private:
  std::chrono::milliseconds srtt_{50};
  std::vector<Clock::time_point> first_sent_;  // per frame of the stream
  std::vector<bool> resent_;
};

}  // namespace host

#endif  // HOST_LIB_STREAM_ROUND_TRIP_TIMER_H
