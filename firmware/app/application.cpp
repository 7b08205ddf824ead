// The firmware application (see application.h and docs/firmware.md).
#include "firmware/app/application.h"

#include <stddef.h>  // offsetof
#include <string.h>  // memcpy

#include "firmware/protocol/codec.h"  // decode_frame

namespace app {

namespace {

const uint8_t kItemsPerPoll = 4;  // command items started per background pass

}  // namespace

Application::Application()
    : link_clock_(0),
      items_stored_(0),
      items_done_(0),
      last_executed_seq_(0),
      override_percent_(100),
      zeroed_(false),
      shown_error_(proto::ErrorCode::kOk) {}

void Application::init(const Board& board, const config::MachineConfig& cfg) {
  link_clock_ = board.link_clock;
  cfg_ = cfg;
  if (!build_axis_scaling(cfg, *board.motion, &scaling_))
    stops_.raise(proto::Alarm::kMotionChipFault);
  executor_.init(scaling_, cfg.capture_radius_um, cfg.default_feed_um_per_s, board.spindle);
  tick_.init(scaling_, board.motion, board.inputs, board.probe);
  dispatcher_.init(board.link, this);
  screen_.init(board.display);
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
    if (first) set_origin_here();
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
    set_origin_here();
    // A session reset's map goes now: the planned position above took the old map's
    // offset off, so the next move returns to the planned depth (as a #A clear does).
    if (stops_.take_map_clear()) executor_.height_map().clear();
  }
  // Also while a stop is under way: the tick may still finish commands as it decelerates.
  while (follower_.item_finished()) finish_oldest();
  job_.track(queue_, follower_.latest(), false);
  if (follower_.jog_ended()) {
    if (executor_.end_jog()) {
      QueueItem* item = queue_.to_execute();
      if (item != 0 && item->kind == ItemKind::kZeroing) {
        queue_.executed();
        finish_oldest();
      }
      if (follower_.latest().jog_confirmed) zeroed_ = true;
      set_origin_here();
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
  if (partly != 0 && executor_.started(*partly)) queue_.executed();
  // The first job command dropped unstarted follows the executing ones in the progress.
  job_.dropping(queue_);
  queue_.drop_waiting();
  store_.clear();
  executor_.drop();
  map_rx_.drop();
}

// The planner continues from where the machine is now.
void Application::set_origin_here() {
  int32_t at[config::kAxisCount];
  position_um(at);
  executor_.planner().set_origin(at);
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
  if (executor_.jog_active() || follower_.latest().mode == (uint8_t)TickMode::kJog)
    return proto::MachineState::kZeroing;
  if (executor_.paused()) return proto::MachineState::kPaused;
  if (stops_.hold_requested())
    return follower_.latest().at_rest ? proto::MachineState::kHeld : proto::MachineState::kHolding;
  if (stops_.stopping() || !queue_.empty() || !follower_.latest().finished ||
      !follower_.latest().at_rest)
    return proto::MachineState::kRunning;
  return proto::MachineState::kIdle;
}

void Application::position_um(int32_t out[config::kAxisCount]) const {
  follower_.position_um(scaling_, out);
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
  executor_.probes().fill(r);
}

// A new session starts without a height map: one left from an earlier job must never
// compensate the next (the host sends the map again with every job that has one).
void Application::reset_session() {
  begin_stop();
  stops_.clear_map_at_stop();  // once the stop has kept the planned position under the map
  items_stored_ = 0;
  items_done_ = 0;
}

void Application::fill_status(proto::StatusReply* r) {
  r->state = state();
  r->alarm = alarm();
  r->flags = (uint8_t)((zeroed_ ? proto::kStatusZeroed : 0) |
                       (stops_.link_hold() ? proto::kStatusLinkHold : 0) |
                       (items_done_ != 0 ? proto::kStatusExecuted : 0) | job_.status_flags());
  // queue_free, next_expected_seq, last_error, rejected_frames: the dispatcher's.
  r->override_percent = override_percent_;
  r->last_executed_seq = last_executed_seq_;
  // x, y, z are adjacent in the reply: written in place.
  static_assert(offsetof(proto::StatusReply, y_um) == offsetof(proto::StatusReply, x_um) + 4 &&
                    offsetof(proto::StatusReply, z_um) == offsetof(proto::StatusReply, x_um) + 8,
                "StatusReply x_um, y_um, z_um adjacent");
  position_um(&r->x_um);
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
  // x, y, z adjacent in the reply as in travel_um: one copy.
  static_assert(offsetof(proto::SessionReply, travel_y_um) ==
                        offsetof(proto::SessionReply, travel_x_um) + 4 &&
                    offsetof(proto::SessionReply, travel_z_um) ==
                        offsetof(proto::SessionReply, travel_x_um) + 8 &&
                    config::kAxisX == 0 && config::kAxisY == 1 && config::kAxisZ == 2,
                "SessionReply travel_x_um, travel_y_um, travel_z_um adjacent, in axis order");
  memcpy(&r->travel_x_um, scaling_.travel_um, sizeof scaling_.travel_um);
  const uint32_t xy =
      cfg_.axis[config::kAxisX].max_speed_um_per_s < cfg_.axis[config::kAxisY].max_speed_um_per_s
          ? cfg_.axis[config::kAxisX].max_speed_um_per_s
          : cfg_.axis[config::kAxisY].max_speed_um_per_s;
  const uint32_t z = cfg_.axis[config::kAxisZ].max_speed_um_per_s;
  r->max_feed_xy_um_per_s = xy > 65535UL ? 65535U : (uint16_t)xy;
  r->max_feed_z_um_per_s = z > 65535UL ? 65535U : (uint16_t)z;
}

// ---------------------------------------------------------------- execution

// Starts queued items in order (item_executor.h).
void Application::execute() {
  if (stops_.stopping() || alarm_active()) return;
  ExecutionContext c = {&tick_,    &follower_,   &store_, &screen_,           &stops_,
                        &scaling_, rapid_feed(), false,   proto::Alarm::kNone};
  for (uint8_t n = 0; n < kItemsPerPoll; ++n) {
    QueueItem* item = queue_.to_execute();
    if (item == 0) return;
    c.standing_still = standing_still();
    if (!executor_.run(item, &c)) {  // waiting (ring full, data missing, zeroing), or an alarm
      if (c.alarm != proto::Alarm::kNone) raise_alarm(c.alarm);
      return;
    }
    queue_.executed();
  }
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
  info.paused = executor_.paused();
  info.probing = executor_.probing();
  info.probe_closed = follower_.latest().probe_closed != 0;
  info.items_done = items_done_;
  info.items_stored = items_stored_;
  position_um(info.pos_um);
  screen_.update(info, tick_.ms());
}

}  // namespace app
