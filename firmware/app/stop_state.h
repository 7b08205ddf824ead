// Stopping, holds and alarms as the background loop keeps them: a stop under way (and a
// stop request still owed to a full ring), a feed hold asked for (by #H or the link
// watchdog), the alarm the background loop raised and the one last reported to the host.
// The tick's own latched alarm comes through TickFollower. Background loop only.
#ifndef FIRMWARE_APP_STOP_STATE_H
#define FIRMWARE_APP_STOP_STATE_H

#include "firmware/protocol/wire_codes.h"  // Alarm

namespace app {

class StopState {
 public:
  StopState()
      : stopping_(false),
        request_owed_(false),
        hold_requested_(false),
        link_hold_(false),
        alarm_(proto::Alarm::kNone),
        reported_(proto::Alarm::kNone),
        map_clear_owed_(false) {}

  // A stop began (the job is dropped): holds end with it; request_sent false: the tick's
  // request ring was full, the request is owed until request_sent_late().
  void started(bool request_sent) {
    stopping_ = true;
    hold_requested_ = false;
    link_hold_ = false;
    if (!request_sent) request_owed_ = true;
  }
  bool request_owed() const { return request_owed_; }
  void request_sent_late() { request_owed_ = false; }
  // The tick dropped its ring (the stop is over unless a later one is still owed).
  void completed() {
    if (!request_owed_) stopping_ = false;
  }
  bool stopping() const { return stopping_; }

  // A session reset's height map goes when its stop completes (so the planned position
  // taken then has the old map's offset off), unless a #A executed first replaced it.
  void clear_map_at_stop() { map_clear_owed_ = true; }
  void map_replaced() { map_clear_owed_ = false; }
  // True once when the completed stop owes the map's clearing.
  bool take_map_clear() {
    const bool owed = map_clear_owed_;
    map_clear_owed_ = false;
    return owed;
  }

  // A feed hold the tick took (#H; by_link: the link watchdog's), and a resume (#R).
  void held(bool by_link) {
    hold_requested_ = true;
    if (by_link) link_hold_ = true;
  }
  void resumed() {
    hold_requested_ = false;
    link_hold_ = false;
  }
  bool hold_requested() const { return hold_requested_; }
  bool link_hold() const { return link_hold_; }

  // The background loop's alarm: the first one raised stays until #C.
  void raise(proto::Alarm a) {
    if (alarm_ == proto::Alarm::kNone) alarm_ = a;
  }
  proto::Alarm alarm() const { return alarm_; }
  // True once per new alarm state (a, the machine's alarm now) to tell the host about.
  bool report(proto::Alarm a) {
    if (a == reported_) return false;
    reported_ = a;
    return true;
  }
  // #C sent: no alarm, holds gone, a stop under way until the tick confirms the ring is
  // dropped.
  void alarm_cleared() {
    alarm_ = proto::Alarm::kNone;
    stopping_ = true;
    hold_requested_ = false;
    link_hold_ = false;
    reported_ = proto::Alarm::kNone;
  }

 private:
  bool stopping_;
  bool request_owed_;
  bool hold_requested_;
  bool link_hold_;
  proto::Alarm alarm_;
  proto::Alarm reported_;
  bool map_clear_owed_;  // #I: the map goes when its stop completes
};

}  // namespace app

#endif  // FIRMWARE_APP_STOP_STATE_H
