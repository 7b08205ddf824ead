// The sender's retransmission timer: the round trip smoothed (1/8 gain) over frames
// acknowledged at their first sending (Karn's rule: a frame sent again, or held by the
// controller for room, says nothing about the link), and the time-out it gives.
#ifndef HOST_LIB_STREAM_ROUND_TRIP_TIMER_H
#define HOST_LIB_STREAM_ROUND_TRIP_TIMER_H

#include <algorithm>  // std::max
#include <chrono>     // std::chrono
#include <cstddef>    // size_t
#include <deque>      // std::deque

namespace host {

class RoundTripTimer {
 public:
  using Clock = std::chrono::steady_clock;

  // A new stream (sampling false: no samples at all, as for the zeroing frame).
  void start(bool sampling) {
    sampling_ = sampling;
    sent_.clear();
    base_ = 0;
  }
  // Frame `index` went out at `t`; again: it gives no sample any more.
  void sent(size_t index, bool again, Clock::time_point t) {
    if (!sampling_) return;
    if (again) {
      if (index >= base_ && index - base_ < sent_.size()) sent_[index - base_].resent = true;
      return;
    }
    if (sent_.empty()) base_ = index;
    sent_.push_back(Sent{t, false});
  }
  // Frame `index` was acknowledged at `t`.
  void acknowledged(size_t index, Clock::time_point t) {
    if (index < base_ || index - base_ >= sent_.size() || sent_[index - base_].resent) return;
    const auto sample =
        std::chrono::duration_cast<std::chrono::milliseconds>(t - sent_[index - base_].first);
    srtt_ = (7 * srtt_ + sample) / 8;
  }
  // Frames before `index` are acknowledged: their send times are let go.
  void release_before(size_t index) {
    while (base_ < index && !sent_.empty()) {
      sent_.pop_front();
      ++base_;
    }
  }
  std::chrono::milliseconds smoothed() const { return srtt_; }
  // Unacknowledged this long, a frame counts as lost.
  std::chrono::milliseconds timeout(std::chrono::milliseconds floor) const {
    return std::max(floor, 4 * srtt_);
  }

 private:
  std::chrono::milliseconds srtt_{50};
  // Per frame sent and not yet let go, from frame base_ on: when first sent, and whether
  // sent again.
  struct Sent {
    Clock::time_point first;
    bool resent = false;
  };
  bool sampling_ = false;
  std::deque<Sent> sent_;
  size_t base_ = 0;
};

}  // namespace host

#endif  // HOST_LIB_STREAM_ROUND_TRIP_TIMER_H
