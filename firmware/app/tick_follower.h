// The background loop's side of the tick link: the requests it sends (counted), the newest
// status snapshot, and which of the tick's cumulative counts (items finished, stops, jogs)
// it has acted on. Background loop only.
#ifndef FIRMWARE_APP_TICK_FOLLOWER_H
#define FIRMWARE_APP_TICK_FOLLOWER_H

#include <stdint.h>  // int32_t, uint8_t, uint16_t

#include "firmware/app/axis_scaling.h"     // AxisScaling
#include "firmware/app/motion_tick.h"      // MotionTick
#include "firmware/app/tick_link.h"        // TickStatus, RequestKind
#include "firmware/protocol/wire_codes.h"  // Alarm

namespace app {

class TickFollower {
 public:
  TickFollower();
  // Sends a request to the tick; false when its ring is full (nothing sent).
  bool request(MotionTick* tick, RequestKind kind, uint8_t value);
  // Takes the next snapshot (false: none); *first is set when it is the first ever (the
  // counts start from it; the positions are known from now on).
  bool take(MotionTick* tick, bool* first);
  bool have_snapshot() const { return have_snapshot_; }
  const TickStatus& latest() const { return latest_; }
  // The actual position in the latest snapshot, micrometres.
  void position_um(const AxisScaling& scaling, int32_t out[config::kAxisCount]) const;

  // Each true once per event the tick reported, in the snapshots taken so far.
  // A kStop or kClearAlarm request done (ring dropped).
  bool stop_completed() {
    if (latest_.stops_done == seen_stops_) return false;
    seen_stops_ = latest_.stops_done;
    return true;
  }
  // One more ring item's last point reached (call until false).
  bool item_finished() {
    if (seen_items_ == latest_.items_done) return false;
    ++seen_items_;
    return true;
  }
  // A zeroing ended (latest().jog_confirmed: it set the zero).
  bool jog_ended() {
    if (latest_.jogs_done == seen_jogs_) return false;
    seen_jogs_ = latest_.jogs_done;
    return true;
  }

  // A #C went out as the newest request: until the tick has taken it, its snapshots still
  // show the alarm it latched.
  void alarm_clear_sent() {
    alarm_clearing_ = true;
    alarm_clear_mark_ = requests_pushed_;
  }
  // The alarm the tick latched (kNone while none, or while a #C is on its way to it).
  proto::Alarm tick_alarm() const;

 private:
  TickStatus latest_;
  bool have_snapshot_;
  uint16_t seen_items_;
  uint8_t seen_stops_;
  uint8_t seen_jogs_;
  uint8_t requests_pushed_;
  bool alarm_clearing_;       // #C sent, the tick has not taken it yet
  uint8_t alarm_clear_mark_;  // requests_pushed_ when #C was sent
};

}  // namespace app

#endif  // FIRMWARE_APP_TICK_FOLLOWER_H
