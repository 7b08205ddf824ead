// The background loop's side of the tick link (see tick_follower.h).
#include "firmware/app/tick_follower.h"

#include <string.h>  // memset

namespace app {

// Every member starts at zero (the snapshot too): one memset, less code than a store each
// (no virtuals).
TickFollower::TickFollower() {
  memset(static_cast<void*>(this), 0, sizeof *this);
}

bool TickFollower::request(MotionTick* tick, RequestKind kind, uint8_t value) {
  TickRequest r;
  r.kind = kind;
  r.value = value;
  if (!tick->request(r)) return false;
  requests_pushed_ = (uint8_t)(requests_pushed_ + 1U);
  return true;
}

bool TickFollower::take(MotionTick* tick, bool* first) {
  TickStatus s;
  *first = false;
  if (!tick->take_status(&s)) return false;
  latest_ = s;
  // Every request up to the #C one taken: the tick's alarm state is current again.
  if (alarm_clearing_ && (uint8_t)(s.requests_done - alarm_clear_mark_) < 128U)
    alarm_clearing_ = false;
  if (!have_snapshot_) {
    have_snapshot_ = true;
    seen_items_ = s.items_done;
    seen_stops_ = s.stops_done;
    seen_jogs_ = s.jogs_done;
    *first = true;
  }
  return true;
}

proto::Alarm TickFollower::tick_alarm() const {
  if (!alarm_clearing_ && latest_.mode == (uint8_t)TickMode::kAlarm &&
      latest_.alarm != kTickAlarmNone)
    return (proto::Alarm)latest_.alarm;
  return proto::Alarm::kNone;
}

void TickFollower::position_um(const AxisScaling& scaling, int32_t out[config::kAxisCount]) const {
  for (uint8_t i = 0; i < config::kAxisCount; ++i)
    out[i] = usteps_to_um(scaling, i, latest_.pos_usteps[i]);
}

}  // namespace app
