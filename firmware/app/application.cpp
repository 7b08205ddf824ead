// The firmware application (see application.h and docs/firmware.md).
#include "firmware/app/application.h"

#include "firmware/protocol/codec.h"  // decode_frame

namespace app {

namespace {

const uint8_t kItemsPerPoll = 4;     // command items started per background pass
const uint8_t kPointsPerPoll = 8;    // spline points generated per background pass
const uint16_t kProbeSettleMs = 20;  // after a touch, before the retract reads the position

}  // namespace

Application::Application()
    : spindle_(0),
      link_clock_(0),
      item_tag_(0),
      items_stored_(0),
      items_done_(0),
      last_feed_um_s_(1000),
      last_executed_seq_(0),
      override_percent_(100),
      jog_active_(false),
      zeroed_(false),
      spline_started_(false),
      pause_presses_(0),
      wait_start_ms_(0),
      paused_(false),
      spindle_on_(false),
      shown_error_(proto::ErrorCode::kOk),
      probing_(false),
      map_clear_at_stop_(false) {
  map_rx_.points = 0;
  map_rx_.expected = 0;
  map_rx_.lowest = 0;
  map_rx_.highest = 0;
}

void Application::init(const Board& board, const config::MachineConfig& cfg) {
  spindle_ = board.spindle;
  link_clock_ = board.link_clock;
  cfg_ = cfg;
  if (!build_axis_scaling(cfg, *board.motion, &scaling_))
    stops_.raise(proto::Alarm::kMotionChipFault);
  planner_.init(scaling_, default_planner_settings(cfg.capture_radius_um));
  planner_.set_height_map(&map_);
  tick_.init(scaling_, board.motion, board.inputs, board.probe);
  dispatcher_.init(board.link, this);
  screen_.init(board.display);
  if (cfg.default_feed_um_per_s > 0 && cfg.default_feed_um_per_s < 65536UL)
    last_feed_um_s_ = (uint16_t)cfg.default_feed_um_per_s;
}

void Application::tick_1ms() {
  tick_.tick_1ms();
}

// ---------------------------------------------------------------- the background loop

void Application::poll() {
  take_snapshots();
  if (!follower_.have_snapshot()) return;  // the tick has not run yet: positions unknown
  follow_tick_events();
  if (stops_.request_owed() && request(RequestKind::kStop, 0)) stops_.request_sent_late();
  dispatcher_.poll(link_ms());
  if (dispatcher_.last_error() != shown_error_) {
    shown_error_ = dispatcher_.last_error();
    if (shown_error_ != proto::ErrorCode::kOk)
      screen_.show_error(shown_error_, dispatcher_.next_expected(), tick_.ms());
  }
  execute();
  watchdog();
  update_screen();
}

bool Application::request(RequestKind kind, uint8_t value) {
  return follower_.request(&tick_, kind, value);
}

void Application::take_snapshots() {
  bool first = false;
  while (follower_.take(&tick_, &first)) {
    if (first) {
      int32_t at[config::kAxisCount];
      position_um(at);
      planner_.set_origin(at);
    }
  }
}

void Application::follow_tick_events() {
  // A completed stop (abort, session reset, alarm cleared): the ring is gone. What the tick
  // finished while it decelerated along the path counts; then the commands that were
  // executing are forgotten, with where the one cut short got to.
  if (follower_.stop_completed()) {
    while (follower_.item_finished()) finish_oldest();
    // A command cut short stays the first unfinished one (not the first one dropped).
    job_.stop_completed(queue_, follower_.latest());
    queue_.drop_executing();
    stops_.completed();
    int32_t at[config::kAxisCount];
    position_um(at);
    planner_.set_origin(at);
    // A session reset's map goes now: the planned position above took the old map's
    // offset off, so the next move returns to the planned depth (as a #A clear does).
    if (map_clear_at_stop_) {
      map_.clear();
      map_clear_at_stop_ = false;
    }
  }
  // Also while a stop is under way: the tick may still finish commands as it decelerates.
  while (follower_.item_finished()) finish_oldest();
  job_.track(queue_, follower_.latest(), false);
  if (follower_.jog_ended()) {
    if (jog_active_) {
      jog_active_ = false;
      QueueItem* item = queue_.to_execute();
      if (item != 0 && item->kind == ItemKind::kZeroing) {
        queue_.executed();
        finish_oldest();
      }
      if (follower_.latest().jog_confirmed) zeroed_ = true;
      int32_t at[config::kAxisCount];
      position_um(at);
      planner_.set_origin(at);
    }
  }
  // A new alarm from the tick: the job is gone; tell the host once.
  const proto::Alarm a = alarm();
  if (stops_.report(a)) {
    if (a != proto::Alarm::kNone) {
      // Position suspect: a switch stop, or a driver that switched off or lost its supply.
      if (a == proto::Alarm::kLimitSwitch || a == proto::Alarm::kDriverFault ||
          a == proto::Alarm::kPowerLost)
        zeroed_ = false;
      drop_job();
      dispatcher_.send_alarm(a, proto::MachineState::kAlarm);
    }
  }
}

// The oldest item finished executing (its last point was reached).
void Application::finish_oldest() {
  const QueueItem* item = queue_.oldest();
  if (item == 0 || queue_.in_flight() == 0) return;
  if (item->kind == ItemKind::kText)
    screen_.show_text(item->text.row, item->text.chars, item->text.length, tick_.ms());
  if (!stops_.stopping()) {  // a dropped command finishing as the tick stops is not this session's
    last_executed_seq_ = item->seq;
    ++items_done_;
  }
  job_.finished(*item);
  queue_.finished();
}

// Forgets the queued work. What the tick has (points in the ring) stays in the queue until
// the stop completes (follow_tick_events): the tick may finish some of it as it decelerates.
void Application::drop_job() {
  // A spline or drill partly handed to the tick is executing too.
  const QueueItem* partly = queue_.to_execute();
  if (partly != 0 && ((partly->kind == ItemKind::kSpline && spline_started_) ||
                      (partly->kind == ItemKind::kDrill && partly->stage > 0)))
    queue_.executed();
  // The first job command dropped unstarted follows the executing ones in the progress.
  job_.dropping(queue_);
  queue_.drop_waiting();
  store_.clear();
  generator_.stop();
  spline_started_ = false;
  jog_active_ = false;
  paused_ = false;
  probing_ = false;
  map_rx_.points = 0;  // #E frames dropped or not: a new #A first
  set_spindle(false);  // abort, session reset and alarms stop the tool too
}

void Application::set_spindle(bool on) {
  spindle_on_ = on;
  if (spindle_ != 0) spindle_->set_on(on);
}

// Everything handed to the tick is done and the axes stand still.
bool Application::standing_still() const {
  return queue_.in_flight() == 0 && follower_.latest().finished && follower_.latest().at_rest;
}

// Asks the tick to decelerate and drop the ring; the background waits for it to finish.
void Application::begin_stop() {
  drop_job();
  stops_.started(request(RequestKind::kStop, 0));
}

void Application::raise_alarm(proto::Alarm a) {
  stops_.raise(a);
  begin_stop();
}

bool Application::alarm_active() const {
  return alarm() != proto::Alarm::kNone;
}

proto::Alarm Application::alarm() const {
  const proto::Alarm latched = follower_.tick_alarm();
  return latched != proto::Alarm::kNone ? latched : stops_.alarm();
}

proto::MachineState Application::state() const {
  if (alarm_active()) return proto::MachineState::kAlarm;
  if (jog_active_ || follower_.latest().mode == (uint8_t)TickMode::kJog)
    return proto::MachineState::kZeroing;
  if (paused_) return proto::MachineState::kPaused;
  if (stops_.hold_requested())
    return follower_.latest().at_rest ? proto::MachineState::kHeld : proto::MachineState::kHolding;
  if (stops_.stopping() || !queue_.empty() || !follower_.latest().finished ||
      !follower_.latest().at_rest)
    return proto::MachineState::kRunning;
  return proto::MachineState::kIdle;
}

void Application::position_um(int32_t out[config::kAxisCount]) const {
  for (uint8_t i = 0; i < config::kAxisCount; ++i)
    out[i] = usteps_to_um(scaling_, i, follower_.latest().pos_usteps[i]);
}

bool Application::inside_travel(uint8_t axis, int32_t um) const {
  const int32_t t = scaling_.travel_um[axis];
  return um <= t && um >= -t;
}

// Motion frames need a zeroed machine, or a zeroing queued ahead of them.
bool Application::motion_allowed() const {
  if (zeroed_) return true;
  for (uint8_t i = 0; i < queue_.size(); ++i) {
    const QueueItem* it = queue_.at(i);
    if (it != 0 && it->kind == ItemKind::kZeroing) return true;
  }
  return false;
}

// ---------------------------------------------------------------- CommandSink

void Application::fill_probe_result(proto::ProbeResultReply* r) {
  probes_.fill(r);
}

// A new session starts without a height map: one left from an earlier job must never
// compensate the next (the host sends the map again with every job that has one).
void Application::reset_session() {
  begin_stop();
  map_clear_at_stop_ = true;  // once the stop has kept the planned position under the map
  items_stored_ = 0;
  items_done_ = 0;
}

void Application::fill_status(proto::StatusReply* r) {
  r->state = state();
  r->alarm = alarm();
  r->flags = (uint8_t)((zeroed_ ? proto::kStatusZeroed : 0) |
                       (stops_.link_hold() ? proto::kStatusLinkHold : 0) |
                       (items_done_ != 0 ? proto::kStatusExecuted : 0) | job_.status_flags());
  r->override_percent = override_percent_;
  r->queue_free = queue_free();
  r->next_expected_seq = 0;  // filled by the dispatcher
  r->last_executed_seq = last_executed_seq_;
  r->last_error = proto::ErrorCode::kOk;
  int32_t at[config::kAxisCount];
  position_um(at);
  r->x_um = at[0];
  r->y_um = at[1];
  r->z_um = at[2];
  r->rejected_frames = 0;
  r->spline_slots_free = spline_slots_free();
  job_.fill_status(r);
}

uint8_t Application::spline_slots_free() {
  return store_.free_slots();
}

uint8_t Application::queue_free() {
  return queue_.free_slots();
}

void Application::fill_session(proto::SessionReply* r) {
  r->queue_slots = CommandQueue::kCapacity;
  r->firmware_major = config::kFirmwareMajor;
  r->firmware_minor = config::kFirmwareMinor;
  // The travel the controller checks targets against, and the fastest feed of each axis.
  r->travel_x_um = scaling_.travel_um[config::kAxisX];
  r->travel_y_um = scaling_.travel_um[config::kAxisY];
  r->travel_z_um = scaling_.travel_um[config::kAxisZ];
  const uint32_t xy =
      cfg_.axis[config::kAxisX].max_speed_um_per_s < cfg_.axis[config::kAxisY].max_speed_um_per_s
          ? cfg_.axis[config::kAxisX].max_speed_um_per_s
          : cfg_.axis[config::kAxisY].max_speed_um_per_s;
  const uint32_t z = cfg_.axis[config::kAxisZ].max_speed_um_per_s;
  r->max_feed_xy_um_per_s = xy > 65535UL ? 65535U : (uint16_t)xy;
  r->max_feed_z_um_per_s = z > 65535UL ? 65535U : (uint16_t)z;
}

// ---------------------------------------------------------------- execution

// Starts queued items in order: moves and splines become ring points, the rest markers.
void Application::execute() {
  if (stops_.stopping() || alarm_active()) return;
  for (uint8_t n = 0; n < kItemsPerPoll; ++n) {
    QueueItem* item = queue_.to_execute();
    if (item == 0) return;
    if (!execute_item(item)) return;  // waiting (ring full, data missing, zeroing)
    queue_.executed();
    item_tag_ = (uint16_t)(item_tag_ + 1U);
  }
}

bool Application::push_point(const int32_t target[config::kAxisCount], uint16_t feed,
                             uint8_t flags) {
  return planner_.push(tick_.ring(), target, feed, flags, item_tag_);
}

// True when the item is fully handed over (its last ring entry flagged end-of-item).
bool Application::execute_item(QueueItem* item) {
  const int32_t* last = planner_.last_um();
  int32_t target[config::kAxisCount] = {last[0], last[1], last[2]};
  switch (item->kind) {
    case ItemKind::kText:
      return push_point(target, last_feed_um_s_, kPointEndOfItem);
    case ItemKind::kResolution:
      generator_.set_resolution(item->resolution.max_step_um, item->resolution.chord_tolerance_um);
      return push_point(target, last_feed_um_s_, kPointEndOfItem);
    case ItemKind::kFeedMove:
    case ItemKind::kRapidMove:
      target[0] = item->move.x_um;
      target[1] = item->move.y_um;
      last_feed_um_s_ = item->move.feed_um_s;
      return push_point(
          target, item->move.feed_um_s,
          (uint8_t)(kPointEndOfItem | (item->kind == ItemKind::kRapidMove ? kPointRapid : 0)));
    case ItemKind::kZMove:
      target[2] = item->z_move.z_um;
      last_feed_um_s_ = item->z_move.feed_um_s;
      return push_point(target, item->z_move.feed_um_s, kPointEndOfItem);
    case ItemKind::kZeroing:
      // Only from a standstill with everything before it finished.
      if (jog_active_ || !standing_still()) return false;
      if (request(RequestKind::kStartJog, item->zeroing.axes)) jog_active_ = true;
      return false;  // completed when the tick reports the end of zeroing
    case ItemKind::kPause:
      // Stage 0: wait for a standstill, show the text; 1: wait for the confirm button.
      if (item->stage == 0) {
        if (!standing_still()) return false;
        screen_.show_pause(item->text.chars, item->text.length);
        pause_presses_ = follower_.latest().confirm_presses;
        paused_ = true;
        item->stage = 1;
      }
      if (item->stage == 1) {
        if (follower_.latest().confirm_presses == pause_presses_) return false;
        paused_ = false;
        item->stage = 2;
      }
      return push_point(target, last_feed_um_s_, kPointEndOfItem);
    case ItemKind::kDwell:
      if (item->stage == 0) {
        if (!standing_still()) return false;
        wait_start_ms_ = follower_.latest().ms;
        item->stage = 1;
      }
      if (item->stage == 1) {
        if ((uint16_t)(follower_.latest().ms - wait_start_ms_) < item->dwell.dwell_ms) return false;
        item->stage = 2;
      }
      return push_point(target, last_feed_um_s_, kPointEndOfItem);
    case ItemKind::kSpindle:
      // Switched at a standstill: never while the tool is still cutting or about to.
      if (item->stage == 0) {
        if (!standing_still()) return false;
        set_spindle(item->spindle.on != 0);
        item->stage = 1;
      }
      return push_point(target, last_feed_um_s_, kPointEndOfItem);
    case ItemKind::kDrill:
      return execute_drill(item);
    case ItemKind::kProbe:
      return execute_probe(item);
    case ItemKind::kMapHeader:
      // In queue order: the points before it keep the old map, those after follow the new.
      map_clear_at_stop_ = false;  // a new session's own map (or clear) wins
      if (item->map_header.cols == 0) {
        map_.clear();
      } else {
        map_.begin(item->map_header.cols, item->map_header.rows, item->map_header.x0_um,
                   item->map_header.y0_um, item->map_header.pitch_x_um,
                   item->map_header.pitch_y_um);
      }
      // Where the machine already goes (no offset added, so no motion): the change applies
      // from the next point generated, never to the standing tool.
      return planner_.push_standing(tick_.ring(), last_feed_um_s_, kPointEndOfItem, item_tag_);
    case ItemKind::kMapHeights: {
      const MapHeightsArgs& m = item->map_heights;
      for (uint8_t i = 0; i < m.n; ++i) map_.set((uint16_t)(m.index + i), m.height_um[i]);
      // The frame that ends the grid (checked when it was stored) switches it on.
      if ((uint16_t)(m.index + m.n) == (uint16_t)map_.cols() * map_.rows()) map_.complete();
      return planner_.push_standing(tick_.ring(), last_feed_um_s_, kPointEndOfItem, item_tag_);
    }
    case ItemKind::kSpline: {
      const uint8_t slot = item->spline.slot;
      const SlotState s = store_.state(slot);
      if (s == SlotState::kFilling) return false;  // data still arriving
      if (s != SlotState::kReady) {
        // Rejected at its last #D (already reported): nothing to run, keep the order.
        store_.release(slot);
        return push_point(target, last_feed_um_s_, kPointEndOfItem);
      }
      if (!spline_started_) {
        if (generator_.begin(store_.spline(slot), item->spline.feed_um_s, last[2], item_tag_,
                             item->spline.tool_offset_um,
                             item->spline.first_point) != core::GeometryError::kOk) {
          store_.release(slot);
          raise_alarm(proto::Alarm::kPathFault);
          return false;
        }
        spline_started_ = true;
        last_feed_um_s_ = item->spline.feed_um_s;
      }
      const int32_t travel[2] = {scaling_.travel_um[0], scaling_.travel_um[1]};
      const GenStatus g = generator_.run(&planner_, tick_.ring(), travel, kPointsPerPoll);
      if (g == GenStatus::kMore) return false;
      spline_started_ = false;
      store_.release(slot);
      if (g == GenStatus::kDone) return true;
      raise_alarm(g == GenStatus::kOutside ? proto::Alarm::kSoftLimit : proto::Alarm::kPathFault);
      return false;
    }
  }
  return false;
}

// #L as ring points, one stage per point (a full ring retries the same stage later):
// 0 up to the start height if below it, 1 X/Y at that travel height, 2 down to the start
// height, 3 plunge at the feed, 4 back up to the start height (end of the item).
bool Application::execute_drill(QueueItem* item) {
  const DrillArgs& d = item->drill;
  const uint8_t rapid = kPointRapid;
  while (item->stage < 5) {
    const int32_t* last = planner_.last_um();
    int32_t target[config::kAxisCount] = {last[0], last[1], last[2]};
    uint16_t feed = rapid_feed();
    uint8_t flags = rapid;
    bool skip = false;
    switch (item->stage) {
      case 0:
        skip = last[2] >= d.z_start_um;
        target[2] = d.z_start_um;
        break;
      case 1:
        skip = last[0] == d.x_um && last[1] == d.y_um;
        target[0] = d.x_um;
        target[1] = d.y_um;
        break;
      case 2:
        skip = last[2] == d.z_start_um;
        target[2] = d.z_start_um;
        break;
      case 3:
        target[2] = d.z_bottom_um;
        feed = d.feed_um_s;
        flags = 0;
        break;
      default:
        target[2] = d.z_start_um;
        flags = (uint8_t)(rapid | kPointEndOfItem);
        break;
    }
    if (!skip && !push_point(target, feed, flags)) return false;
    item->stage = (uint8_t)(item->stage + 1U);
  }
  last_feed_um_s_ = d.feed_um_s;
  return true;
}

// #Y: 0 the checks at a standstill, then the descent to z_limit (machine Z, no map offset);
// 1 wait for the tick's verdict; 2 let Z come to rest, then retract above the contact.
bool Application::execute_probe(QueueItem* item) {
  ProbeArgs& p = item->probe;
  int32_t at[config::kAxisCount];
  if (item->stage == 0) {
    if (!standing_still()) return false;
    if (!tick_.has_probe()) {
      raise_alarm(proto::Alarm::kProbeMissing);
      return false;
    }
    if (spindle_on_) {
      raise_alarm(proto::Alarm::kProbeSpindleOn);
      return false;
    }
    if (follower_.latest().probe_closed) {
      raise_alarm(proto::Alarm::kProbeClosedAtStart);
      return false;
    }
    position_um(at);
    if (p.z_limit_um >= at[config::kAxisZ]) {  // nothing below to probe: nothing moves
      probes_.note(2, at);
      raise_alarm(proto::Alarm::kProbeNoContact);
      return false;
    }
    const int32_t* m = planner_.machine_um();
    const int32_t target[config::kAxisCount] = {m[0], m[1], p.z_limit_um};
    p.seen_probes = follower_.latest().probes_done;
    if (!planner_.push_machine(tick_.ring(), target, p.feed_um_s, kPointProbe, item_tag_))
      return false;
    probing_ = true;
    item->stage = 1;
  }
  if (item->stage == 1) {
    if (follower_.latest().probes_done == p.seen_probes) return false;
    position_um(at);
    const uint8_t result = tick_.probe_result();  // handed over in ProbeWatch (motion_tick.h)
    at[config::kAxisZ] = usteps_to_um(scaling_, config::kAxisZ, tick_.probe_z_usteps());
    probes_.note(result, at);
    if (result != 1) {
      probing_ = false;
      raise_alarm(proto::Alarm::kProbeNoContact);
      return false;
    }
    wait_start_ms_ = follower_.latest().ms;
    item->stage = 2;
  }
  if (item->stage == 2) {
    // The tick dropped the descent; the chip ramps Z down from the probe feed meanwhile.
    if ((uint16_t)(follower_.latest().ms - wait_start_ms_) < kProbeSettleMs) return false;
    position_um(at);
    planner_.set_origin(at);
    item->stage = 3;
  }
  const int32_t* m = planner_.machine_um();
  const int32_t up[config::kAxisCount] = {m[0], m[1], probes_.z_um() + p.retract_um};
  if (!planner_.push_machine(tick_.ring(), up, rapid_feed(), kPointEndOfItem, item_tag_))
    return false;
  probing_ = false;
  return true;
}

// Link watchdog: running with no valid frame for kLinkTimeoutMs -> feed hold.
void Application::watchdog() {
  if (!dispatcher_.session_open() || stops_.hold_requested()) return;
  if (state() != proto::MachineState::kRunning) return;
  if (dispatcher_.ms_since_valid(link_ms()) < (uint16_t)proto::kLinkTimeoutMs) return;
  if (request(RequestKind::kLinkHold, 0)) stops_.held(true);
}

// The link's time-outs count the board's link clock, else the tick (link_clock.h).
uint16_t Application::link_ms() const {
  return link_clock_ != 0 ? link_clock_->link_ms() : tick_.ms();
}

void Application::update_screen() {
  ScreenInfo info;
  info.state = state();
  info.alarm = alarm();
  info.zeroed = zeroed_;
  info.z_mode = follower_.latest().z_mode != 0;  // the tick's jog state, through its snapshot
  info.paused = paused_;
  info.probing = probing_;
  info.probe_closed = follower_.latest().probe_closed != 0;
  info.items_done = items_done_;
  info.items_stored = items_stored_;
  position_um(info.pos_um);
  screen_.update(info, tick_.ms());
}

}  // namespace app
