// The application's command handlers: one per command of the message table, named in its
// handler column. Queued commands become queue items (after the checks that need the
// machine: zeroed, inside the travel); real-time ones act at once. Background loop only.
#include "firmware/app/application.h"

#include <string.h>  // memcpy, memset

#include "firmware/protocol/codec.h"  // decode_command

namespace app {

using proto::ErrorCode;

// Decodes the frame as its table row's message (one walker, proto::decode_command_row) and
// calls that row's handler (#I, #? and #T never come here: the dispatcher answers them). The
// letter is looked up once, by proto::command_row, for both.
ErrorCode Application::handle(const proto::Frame& f, uint8_t* detail) {
  typedef ErrorCode (*CommandCall)(Application * app, const proto::AnyCommand& m, uint8_t seq,
                                   uint8_t* detail);
  static const CommandCall kRoutes[] = {APP_COMMAND_ROUTES()};
  *detail = 0;
  const uint8_t row = proto::command_row(f.letter);
  if (row == proto::kNoCommandRow || kRoutes[row] == 0) return ErrorCode::kUnknownCommand;
  proto::AnyCommand m;
  const ErrorCode e = proto::decode_command_row(row, f.payload, f.length, &m);
  if (e != ErrorCode::kOk) return e;
  return kRoutes[row](this, m, f.seq, detail);
}

ErrorCode Application::store(const proto::Frame& f, uint8_t* detail) {
  if (alarm_active()) {
    *detail = 0;
    return ErrorCode::kAlarmActive;
  }
  return handle(f, detail);
}

ErrorCode Application::realtime(const proto::Frame& f) {
  uint8_t detail = 0;
  return handle(f, &detail);
}

// A queued command's item: its arguments (the union member of its kind, or for a command
// kept as it arrived the command struct itself: the union member is that struct, or starts
// with it) copied in, the rest zero but job_index. One copy for every kind.
ErrorCode Application::enqueue_args(ItemKind kind, uint8_t seq, const void* args, uint8_t size) {
  QueueItem item;
  memset(&item, 0, sizeof item);
  item.kind = kind;
  item.seq = seq;
  item.job_index = kNotInJob;
  memcpy(&item.text, args, size);  // &item.text: the start of the arguments' union
  // After a #J it gets the next job index (and a spline the mark's first point).
  job_.number(&item);
  if (!queue_.push(item)) return ErrorCode::kBusy;
  ++items_stored_;
  job_.stored();
  return ErrorCode::kOk;
}

// Numbers the commands that follow (job_progress.h).
ErrorCode Application::on_job_mark(const proto::JobMarkCmd& c, uint8_t, uint8_t*) {
  job_.mark(c);
  job_.track(queue_, follower_.latest(), false);
  return ErrorCode::kOk;
}

// Motion frames need a zeroed machine (or a zeroing queued ahead) and a target inside the
// travel of every axis named.
ErrorCode Application::motion_check(const int32_t* x_um, const int32_t* y_um,
                                    const int32_t* z_um) const {
  if (!motion_allowed()) return ErrorCode::kNotZeroed;
  if ((x_um != 0 && !inside_travel(config::kAxisX, *x_um)) ||
      (y_um != 0 && !inside_travel(config::kAxisY, *y_um)) ||
      (z_um != 0 && !inside_travel(config::kAxisZ, *z_um)))
    return ErrorCode::kOutOfTravel;
  return ErrorCode::kOk;
}

uint16_t Application::rapid_feed() const {
  return cfg_.rapid_feed_um_per_s > 65535UL ? 65535U : (uint16_t)cfg_.rapid_feed_um_per_s;
}

// ---- queued ----

ErrorCode Application::on_text(const proto::TextCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_text(ItemKind::kText, seq, c.row, c.text, c.length);
}

ErrorCode Application::on_pause(const proto::PauseCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_text(ItemKind::kPause, seq, 0, c.text, c.length);
}

// #S and #P: a line of text for the LCD.
ErrorCode Application::enqueue_text(ItemKind kind, uint8_t seq, uint8_t row, const char* text,
                                    uint8_t length) {
  TextArgs args;
  args.row = row;
  args.length = length;
  memcpy(args.chars, text, length);
  return enqueue_args(kind, seq, &args, sizeof args);
}

ErrorCode Application::on_dwell(const proto::DwellCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_args(ItemKind::kDwell, seq, &c, sizeof(DwellArgs));
}

ErrorCode Application::on_spindle(const proto::SpindleCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_args(ItemKind::kSpindle, seq, &c, sizeof(SpindleArgs));
}

ErrorCode Application::on_resolution(const proto::ResolutionCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_args(ItemKind::kResolution, seq, &c, sizeof(ResolutionArgs));
}

ErrorCode Application::on_feed_move(const proto::FeedMoveCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_move(ItemKind::kFeedMove, seq, &c.x_um, &c.y_um, c.feed_um_per_s);
}

ErrorCode Application::on_rapid_move(const proto::RapidMoveCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_move(ItemKind::kRapidMove, seq, &c.x_um, &c.y_um, rapid_feed());
}

// #G and #F: an X/Y move inside the travel.
ErrorCode Application::enqueue_move(ItemKind kind, uint8_t seq, const int32_t* x_um,
                                    const int32_t* y_um, uint16_t feed_um_s) {
  MoveArgs move;
  move.x_um = *x_um;
  move.y_um = *y_um;
  move.feed_um_s = feed_um_s;
  return enqueue_inside(kind, seq, &move, sizeof move, x_um, y_um, 0);
}

// enqueue_args of a motion command whose targets (the axes named) pass motion_check.
ErrorCode Application::enqueue_inside(ItemKind kind, uint8_t seq, const void* args, uint8_t size,
                                      const int32_t* x_um, const int32_t* y_um,
                                      const int32_t* z_um) {
  const ErrorCode e = motion_check(x_um, y_um, z_um);
  return e != ErrorCode::kOk ? e : enqueue_args(kind, seq, args, size);
}

ErrorCode Application::on_z_move(const proto::ZMoveCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_inside(ItemKind::kZMove, seq, &c, sizeof(ZMoveArgs), 0, 0, &c.z_um);
}

ErrorCode Application::on_drill(const proto::DrillCmd& c, uint8_t seq, uint8_t*) {
  const ErrorCode e = motion_check(0, 0, &c.z_bottom_um);  // the same codes in either order
  if (e != ErrorCode::kOk) return e;
  return enqueue_inside(ItemKind::kDrill, seq, &c, sizeof(DrillArgs), &c.x_um, &c.y_um,
                        &c.z_start_um);
}

// #Y: machine Z, so the limit must lie inside the Z travel; the rest is checked when it runs
// (spindle, probe input, the Z it starts from).
ErrorCode Application::on_probe(const proto::ProbeCmd& c, uint8_t seq, uint8_t*) {
  return enqueue_inside(ItemKind::kProbe, seq, &c, sizeof c, 0, 0, &c.z_limit_um);
}

ErrorCode Application::on_height_map_header(const proto::HeightMapHeaderCmd& c, uint8_t seq,
                                            uint8_t*) {
  const ErrorCode e = enqueue_args(ItemKind::kMapHeader, seq, &c, sizeof(MapHeaderArgs));
  if (e == ErrorCode::kOk) map_rx_.announced((uint16_t)((uint16_t)c.cols * c.rows));
  return e;
}

// #E: the next heights of the map announced by #A, in order (map_reception.h).
ErrorCode Application::on_height_map_data(const proto::HeightMapDataCmd& c, uint8_t seq,
                                          uint8_t* detail) {
  MapHeightsArgs args;
  MapSpan span;
  ErrorCode e = map_rx_.check(c, &args, &span, detail);
  if (e == ErrorCode::kOk) e = enqueue_args(ItemKind::kMapHeights, seq, &args, sizeof args);
  if (e == ErrorCode::kOk) map_rx_.accepted(args, span);
  return e;
}

ErrorCode Application::on_zeroing(const proto::ZeroingCmd& c, uint8_t seq, uint8_t*) {
  if (!queue_.empty() || stops_.stopping()) return ErrorCode::kBadState;
  return enqueue_args(ItemKind::kZeroing, seq, &c.axes, sizeof c.axes);
}

ErrorCode Application::on_spline_header(const proto::SplineHeaderCmd& c, uint8_t seq, uint8_t*) {
  if (!motion_allowed()) return ErrorCode::kNotZeroed;
  if (queue_.free_slots() == 0 || !store_.has_free_slot()) return ErrorCode::kBusy;
  uint8_t slot = 0;
  const ErrorCode e = store_.begin(c, &slot);
  if (e != ErrorCode::kOk) return e;
  SplineArgs args;
  args.slot = slot;
  args.feed_um_s = c.feed_um_per_s;
  args.tool_offset_um = c.tool_offset_um;
  args.first_point = 0;
  return enqueue_args(ItemKind::kSpline, seq, &args, sizeof args);
}

// Stored in the spline's slot, no queue item of its own.
ErrorCode Application::on_spline_data(const proto::SplineDataCmd& c, uint8_t, uint8_t* detail) {
  bool completed = false;
  return store_.add(c, scaling_.travel_um, detail, &completed);
}

ErrorCode Application::on_spline_compact(const proto::SplineCompactCmd& c, uint8_t,
                                         uint8_t* detail) {
  bool completed = false;
  return store_.add_compact(c, scaling_.travel_um, detail, &completed);
}

ErrorCode Application::on_spline_contour(const proto::SplineContourCmd& c, uint8_t,
                                         uint8_t* detail) {
  bool completed = false;
  return store_.add_contour(c, scaling_.travel_um, detail, &completed);
}

// ---- real-time ----

ErrorCode Application::on_hold(const proto::HoldCmd&, uint8_t, uint8_t*) {
  if (!request(RequestKind::kHold, 0)) return ErrorCode::kBusy;
  stops_.held(false);
  return ErrorCode::kOk;
}

ErrorCode Application::on_resume(const proto::ResumeCmd&, uint8_t, uint8_t*) {
  if (!stops_.hold_requested()) return ErrorCode::kBadState;
  if (!request(RequestKind::kResume, 0)) return ErrorCode::kBusy;
  stops_.resumed();
  return ErrorCode::kOk;
}

ErrorCode Application::on_abort(const proto::AbortCmd&, uint8_t, uint8_t*) {
  begin_stop();
  dispatcher_.abort_stream();
  return ErrorCode::kOk;
}

ErrorCode Application::on_override(const proto::OverrideCmd& c, uint8_t, uint8_t*) {
  if (!request(RequestKind::kOverride, c.percent)) return ErrorCode::kBusy;
  override_percent_ = c.percent;
  return ErrorCode::kOk;
}

ErrorCode Application::on_clear_alarm(const proto::ClearAlarmCmd&, uint8_t, uint8_t*) {
  if (!alarm_active()) return ErrorCode::kBadState;
  if (!request(RequestKind::kClearAlarm, 0)) return ErrorCode::kBusy;
  drop_job();
  stops_.alarm_cleared();  // a stop until the tick confirms the ring is dropped
  // Snapshots taken before the tick saw the request still show the latched alarm.
  follower_.alarm_clear_sent();
  return ErrorCode::kOk;
}

}  // namespace app
