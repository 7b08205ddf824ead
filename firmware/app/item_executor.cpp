// Item execution (see item_executor.h and docs/firmware.md).
#include "firmware/app/item_executor.h"

#include <string.h>  // memcpy, memcmp, memset

namespace app {

namespace {

const uint8_t kPointsPerPoll = 8;    // spline points generated per background pass
const uint16_t kProbeSettleMs = 20;  // after a touch, before the retract reads the position

}  // namespace

ItemExecutor::ItemExecutor() : spindle_(0), spindle_on_(false) {
  // item_tag_ up to probing_ (declared in that order) start at zero: one memset of the
  // block, less code than a store per member.
  uint8_t* const first = reinterpret_cast<uint8_t*>(&item_tag_);
  memset(first, 0, (size_t)(reinterpret_cast<uint8_t*>(&probing_ + 1) - first));
  last_feed_um_s_ = 1000;
}

bool ItemExecutor::run(QueueItem* item, ExecutionContext* c) {
  if (!dispatch(item, c)) return false;
  item_tag_ = (uint16_t)(item_tag_ + 1U);
  return true;
}

void ItemExecutor::drop() {
  generator_.stop();
  spline_started_ = false;
  jog_active_ = false;
  paused_ = false;
  probing_ = false;
  set_spindle(false);  // abort, session reset and alarms stop the tool too
}

void ItemExecutor::set_spindle(bool on) {
  spindle_on_ = on;
  if (spindle_ != 0) spindle_->set_on(on);
}

inline bool ItemExecutor::dispatch(QueueItem* item, ExecutionContext* c) {
  switch (item->kind) {
    case ItemKind::kText:
      return push_marker(c);
    case ItemKind::kResolution:
      generator_.set_resolution(item->resolution.max_step_um, item->resolution.chord_tolerance_um);
      return push_marker(c);
    case ItemKind::kFeedMove:
    case ItemKind::kRapidMove:
      return run_move(*item, c);
    case ItemKind::kZMove:
      return run_z_move(item->z_move, c);
    case ItemKind::kZeroing:
      return run_zeroing(item->zeroing, c);
    case ItemKind::kPause:
      return run_pause(item, c);
    case ItemKind::kDwell:
      return run_dwell(item, c);
    case ItemKind::kSpindle:
      return run_spindle(item, c);
    case ItemKind::kDrill:
      return run_drill(item, c);
    case ItemKind::kProbe:
      return run_probe(item, c);
    case ItemKind::kMapHeader:
      return run_map_header(item->map_header, c);
    case ItemKind::kMapHeights:
      return run_map_heights(item->map_heights, c);
    case ItemKind::kSpline:
      return run_spline(item->spline, c);
  }
  return false;
}

bool ItemExecutor::push_point(const int32_t target[config::kAxisCount], uint16_t feed,
                              uint8_t flags, ExecutionContext* c) {
  return planner_.push(c->tick->ring(), target, feed, flags, item_tag_);
}

// Ends the item where the machine already is (nothing moves).
bool ItemExecutor::push_marker(ExecutionContext* c) {
  return push_point(planner_.last_um(), last_feed_um_s_, kPointEndOfItem, c);
}

// Straight up or down to z_um from where the machine is (machine coordinates: no map offset).
bool ItemExecutor::push_machine_z(int32_t z_um, uint16_t feed, uint8_t flags, ExecutionContext* c) {
  int32_t target[config::kAxisCount];
  memcpy(target, planner_.machine_um(), sizeof target);
  target[config::kAxisZ] = z_um;
  return planner_.push_machine(c->tick->ring(), target, feed, flags, item_tag_);
}

inline bool ItemExecutor::run_move(const QueueItem& item, ExecutionContext* c) {
  const int32_t target[config::kAxisCount] = {item.move.x_um, item.move.y_um,
                                              planner_.last_um()[2]};
  last_feed_um_s_ = item.move.feed_um_s;
  const uint8_t rapid = item.kind == ItemKind::kRapidMove ? kPointRapid : 0;
  return push_point(target, item.move.feed_um_s, (uint8_t)(kPointEndOfItem | rapid), c);
}

inline bool ItemExecutor::run_z_move(const ZMoveArgs& z, ExecutionContext* c) {
  int32_t target[config::kAxisCount];
  memcpy(target, planner_.last_um(), sizeof target);
  target[config::kAxisZ] = z.z_um;
  last_feed_um_s_ = z.feed_um_per_s;
  return push_point(target, z.feed_um_per_s, kPointEndOfItem, c);
}

// Only from a standstill with everything before it finished; completed when the tick
// reports the end of the zeroing (never here).
inline bool ItemExecutor::run_zeroing(const ZeroingArgs& z, ExecutionContext* c) {
  if (jog_active_ || !c->standing_still) return false;
  if (c->follower->request(c->tick, RequestKind::kStartJog, z.axes)) jog_active_ = true;
  return false;
}

// Stage 0: wait for a standstill, show the text; 1: wait for the confirm button.
inline bool ItemExecutor::run_pause(QueueItem* item, ExecutionContext* c) {
  const TickStatus& now = c->follower->latest();
  if (item->stage == 0) {
    if (!c->standing_still) return false;
    c->screen->show_pause(item->text.chars, item->text.length);
    pause_presses_ = now.confirm_presses;
    paused_ = true;
    item->stage = 1;
  }
  if (item->stage == 1) {
    if (now.confirm_presses == pause_presses_) return false;
    paused_ = false;
    item->stage = 2;
  }
  return push_marker(c);
}

inline bool ItemExecutor::run_dwell(QueueItem* item, ExecutionContext* c) {
  const TickStatus& now = c->follower->latest();
  if (item->stage == 0) {
    if (!c->standing_still) return false;
    wait_start_ms_ = now.ms;
    item->stage = 1;
  }
  if (item->stage == 1) {
    if ((uint16_t)(now.ms - wait_start_ms_) < item->dwell.dwell_ms) return false;
    item->stage = 2;
  }
  return push_marker(c);
}

// Switched at a standstill: never while the tool is still cutting or about to.
inline bool ItemExecutor::run_spindle(QueueItem* item, ExecutionContext* c) {
  if (item->stage == 0) {
    if (!c->standing_still) return false;
    set_spindle(item->spindle.on != 0);
    item->stage = 1;
  }
  return push_marker(c);
}

// #L as ring points, one stage per point (a full ring retries the same stage later):
// 0 up to the start height if below it, 1 X/Y at that travel height, 2 down to the start
// height, 3 plunge at the feed, 4 back up to the start height (end of the item).
inline bool ItemExecutor::run_drill(QueueItem* item, ExecutionContext* c) {
  const DrillArgs& d = item->drill;
  while (item->stage < 5) {
    const uint8_t stage = item->stage;
    const int32_t* last = planner_.last_um();
    int32_t target[config::kAxisCount];
    memcpy(target, last, sizeof target);
    uint16_t feed = c->rapid_feed_um_s;
    uint8_t flags = kPointRapid;
    if (stage == 1) {
      target[0] = d.x_um;
      target[1] = d.y_um;
    } else {
      target[2] = stage == 3 ? d.z_bottom_um : d.z_start_um;
    }
    if (stage == 3) {
      feed = d.feed_um_per_s;
      flags = 0;
    }
    if (stage == 4) flags = (uint8_t)(kPointRapid | kPointEndOfItem);
    // Stage 0 only rises; 1 and 2 are skipped where the tool already is; 3 and 4 always
    // go (4 ends the item).
    const bool skip = stage == 0 ? last[2] >= d.z_start_um
                                 : stage < 3 && memcmp(target, last, sizeof target) == 0;
    if (!skip && !push_point(target, feed, flags, c)) return false;
    item->stage = (uint8_t)(stage + 1U);
  }
  last_feed_um_s_ = d.feed_um_per_s;
  return true;
}

// #Y: 0 the checks at a standstill, then the descent to z_limit (machine Z, no map offset);
// 1 wait for the tick's verdict; 2 let Z come to rest, then retract above the contact.
inline bool ItemExecutor::run_probe(QueueItem* item, ExecutionContext* c) {
  ProbeArgs& p = item->probe;
  if (item->stage == 0) {
    if (!start_probe(&p, c)) return false;
    item->stage = 1;
  }
  if (item->stage == 1) {
    if (!take_probe_verdict(p, c)) return false;
    wait_start_ms_ = c->follower->latest().ms;
    item->stage = 2;
  }
  if (item->stage == 2) {
    // The tick dropped the descent; the chip ramps Z down from the probe feed meanwhile.
    if ((uint16_t)(c->follower->latest().ms - wait_start_ms_) < kProbeSettleMs) return false;
    int32_t at[config::kAxisCount];
    c->follower->position_um(*c->scaling, at);
    planner_.set_origin(at);
    item->stage = 3;
  }
  if (!push_machine_z(probes_.z_um() + p.cmd.retract_um, c->rapid_feed_um_s, kPointEndOfItem, c))
    return false;
  probing_ = false;
  return true;
}

// The checks at a standstill, then the descent; true once it is in the ring.
inline bool ItemExecutor::start_probe(ProbeArgs* p, ExecutionContext* c) {
  if (!c->standing_still) return false;
  const TickStatus& now = c->follower->latest();
  if (!c->tick->has_probe()) {
    c->alarm = proto::Alarm::kProbeMissing;
  } else if (spindle_on_) {
    c->alarm = proto::Alarm::kProbeSpindleOn;
  } else if (now.probe_closed) {
    c->alarm = proto::Alarm::kProbeClosedAtStart;
  }
  if (c->alarm != proto::Alarm::kNone) return false;
  int32_t at[config::kAxisCount];
  c->follower->position_um(*c->scaling, at);
  if (p->cmd.z_limit_um >= at[config::kAxisZ]) {  // nothing below to probe: nothing moves
    probes_.note(2, at);
    c->alarm = proto::Alarm::kProbeNoContact;
    return false;
  }
  p->seen_probes = now.probes_done;
  if (!push_machine_z(p->cmd.z_limit_um, p->cmd.feed_um_per_s, kPointProbe, c)) return false;
  probing_ = true;
  return true;
}

// True once the tick ended the descent at a contact (recorded); no contact raises the alarm.
inline bool ItemExecutor::take_probe_verdict(const ProbeArgs& p, ExecutionContext* c) {
  const TickStatus& now = c->follower->latest();
  if (now.probes_done == p.seen_probes) return false;
  int32_t at[config::kAxisCount];
  c->follower->position_um(*c->scaling, at);
  const uint8_t result = c->tick->probe_result();  // handed over in ProbeWatch (motion_tick.h)
  at[config::kAxisZ] = usteps_to_um(*c->scaling, config::kAxisZ, c->tick->probe_z_usteps());
  probes_.note(result, at);
  if (result == 1) return true;
  probing_ = false;
  c->alarm = proto::Alarm::kProbeNoContact;
  return false;
}

// In queue order: the points before it keep the old map, those after follow the new.
inline bool ItemExecutor::run_map_header(const MapHeaderArgs& h, ExecutionContext* c) {
  c->stops->map_replaced();  // a new session's own map (or clear) wins
  if (h.cols == 0) {
    map_.clear();
  } else {
    map_.begin(h.cols, h.rows, h.x0_um, h.y0_um, h.pitch_x_um, h.pitch_y_um);
  }
  // Where the machine already goes (no offset added, so no motion): the change applies
  // from the next point generated, never to the standing tool.
  return planner_.push_standing(c->tick->ring(), last_feed_um_s_, kPointEndOfItem, item_tag_);
}

inline bool ItemExecutor::run_map_heights(const MapHeightsArgs& m, ExecutionContext* c) {
  for (uint8_t i = 0; i < m.n; ++i) map_.set((uint16_t)(m.index + i), m.height_um[i]);
  // The frame that ends the grid (checked when it was stored) switches it on.
  if ((uint16_t)(m.index + m.n) == (uint16_t)map_.cols() * map_.rows()) map_.complete();
  return planner_.push_standing(c->tick->ring(), last_feed_um_s_, kPointEndOfItem, item_tag_);
}

inline bool ItemExecutor::run_spline(const SplineArgs& s, ExecutionContext* c) {
  const SlotState state = c->store->state(s.slot);
  if (state == SlotState::kFilling) return false;  // data still arriving
  if (state != SlotState::kReady) {
    // Rejected at its last #D (already reported): nothing to run, keep the order.
    c->store->release(s.slot);
    return push_marker(c);
  }
  if (!spline_started_ && !begin_spline(s, c)) return false;
  const GenStatus g =
      generator_.run(&planner_, c->tick->ring(), c->scaling->travel_um, kPointsPerPoll);
  if (g == GenStatus::kMore) return false;
  spline_started_ = false;
  c->store->release(s.slot);
  if (g == GenStatus::kDone) return true;
  c->alarm = g == GenStatus::kOutside ? proto::Alarm::kSoftLimit : proto::Alarm::kPathFault;
  return false;
}

inline bool ItemExecutor::begin_spline(const SplineArgs& s, ExecutionContext* c) {
  if (generator_.begin(c->store->spline(s.slot), s.feed_um_s, planner_.last_um()[2], item_tag_,
                       s.tool_offset_um, s.first_point) != core::GeometryError::kOk) {
    c->store->release(s.slot);
    c->alarm = proto::Alarm::kPathFault;
    return false;
  }
  spline_started_ = true;
  last_feed_um_s_ = s.feed_um_s;
  return true;
}

}  // namespace app
