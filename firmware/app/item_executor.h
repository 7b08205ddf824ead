// Item execution: the queued commands, oldest first, become ring points through the planner
// (moves, splines through the point generator, drills, probes) or markers (a ring entry at
// the current position that ends the item: text, pauses, dwells, the spindle, the height
// map's frames). Owns the planner, the generator, the height map as executed and the state
// of the item under way. Background loop only.
#ifndef FIRMWARE_APP_ITEM_EXECUTOR_H
#define FIRMWARE_APP_ITEM_EXECUTOR_H

#include <stdint.h>  // int32_t, uint8_t, uint16_t

#include "firmware/app/axis_scaling.h"     // AxisScaling
#include "firmware/app/command_queue.h"    // QueueItem
#include "firmware/app/motion_tick.h"      // MotionTick
#include "firmware/app/planner.h"          // Planner
#include "firmware/app/point_generator.h"  // PointGenerator
#include "firmware/app/probe_record.h"     // ProbeRecord
#include "firmware/app/spline_store.h"     // SplineStore
#include "firmware/app/status_screen.h"    // StatusScreen
#include "firmware/app/stop_state.h"       // StopState
#include "firmware/app/tick_follower.h"    // TickFollower
#include "firmware/core/height_map.h"      // HeightMap
#include "firmware/protocol/wire_codes.h"  // Alarm
#include "hal/interfaces/spindle.h"

namespace app {

// What an item needs from the rest of the application, built on the stack for each pass
// (the executor keeps no pointers: no RAM for them).
struct ExecutionContext {
  MotionTick* tick;        // the ring, the probe's hand-over
  TickFollower* follower;  // snapshots; the zeroing request
  SplineStore* store;
  StatusScreen* screen;
  StopState* stops;  // a #A replaces a session reset's pending map clear
  const AxisScaling* scaling;
  uint16_t rapid_feed_um_s;
  bool standing_still;  // set before each item: all handed over is done, the axes at rest
  proto::Alarm alarm;   // out: the alarm an item raised (kNone: none)
};

class ItemExecutor {
 public:
  ItemExecutor();
  void init(const AxisScaling& scaling, uint16_t capture_radius_um, uint32_t default_feed_um_s,
            hal::Spindle* spindle) {
    spindle_ = spindle;
    planner_.init(scaling, default_planner_settings(capture_radius_um));
    planner_.set_height_map(&map_);
    if (default_feed_um_s > 0 && default_feed_um_s < 65536UL)
      last_feed_um_s_ = (uint16_t)default_feed_um_s;
  }

  // True when the item is fully handed over (its last ring entry flagged end-of-item); false
  // while it waits (ring full, data missing, a standstill, the operator) or when it raised
  // c->alarm.
  bool run(QueueItem* item, ExecutionContext* c);
  // Forgets the item under way (a stop): the generator stops, the spindle goes off.
  void drop();
  // The item to execute next has part of it handed to the tick already.
  bool started(const QueueItem& item) const {
    return (item.kind == ItemKind::kSpline && spline_started_) ||
           (item.kind == ItemKind::kDrill && item.stage > 0);
  }
  // A zeroing the tick reported ended: true if one was under way.
  bool end_jog() {
    const bool was = jog_active_;
    jog_active_ = false;
    return was;
  }

  Planner& planner() { return planner_; }
  core::HeightMap& height_map() { return map_; }
  const core::HeightMap& height_map() const { return map_; }
  const ProbeRecord& probes() const { return probes_; }
  bool jog_active() const { return jog_active_; }
  bool paused() const { return paused_; }
  bool probing() const { return probing_; }
  bool spindle_on() const { return spindle_on_; }

 private:
  bool dispatch(QueueItem* item, ExecutionContext* c);
  bool push_point(const int32_t target[config::kAxisCount], uint16_t feed, uint8_t flags,
                  ExecutionContext* c);
  bool push_marker(ExecutionContext* c);
  bool push_machine_z(int32_t z_um, uint16_t feed, uint8_t flags, ExecutionContext* c);
  bool run_move(const QueueItem& item, ExecutionContext* c);
  bool run_z_move(const ZMoveArgs& z, ExecutionContext* c);
  bool run_zeroing(const ZeroingArgs& z, ExecutionContext* c);
  bool run_pause(QueueItem* item, ExecutionContext* c);
  bool run_dwell(QueueItem* item, ExecutionContext* c);
  bool run_spindle(QueueItem* item, ExecutionContext* c);
  bool run_drill(QueueItem* item, ExecutionContext* c);
  bool run_probe(QueueItem* item, ExecutionContext* c);
  bool start_probe(ProbeArgs* p, ExecutionContext* c);
  bool take_probe_verdict(const ProbeArgs& p, ExecutionContext* c);
  bool run_map_header(const MapHeaderArgs& h, ExecutionContext* c);
  bool run_map_heights(const MapHeightsArgs& m, ExecutionContext* c);
  bool run_spline(const SplineArgs& s, ExecutionContext* c);
  bool begin_spline(const SplineArgs& s, ExecutionContext* c);
  void set_spindle(bool on);

  hal::Spindle* spindle_;  // 0: none (Board)
  bool spindle_on_;
  Planner planner_;
  PointGenerator generator_;
  core::HeightMap map_;  // (#A/#E) as executed in queue order, followed by the planner
  ProbeRecord probes_;   // the last probe's result (#T), since power-up
  // item_tag_ to probing_: zeroed as one block by the constructor.
  uint16_t item_tag_;  // of the item under way, on its ring points
  uint16_t last_feed_um_s_;
  bool spline_started_;
  bool jog_active_;         // a zeroing item asked the tick to jog
  uint8_t pause_presses_;   // confirm_presses when the pause started
  uint16_t wait_start_ms_;  // tick ms when the dwell (or the probe's settling) started
  bool paused_;             // a #P waits for the operator
  bool probing_;            // a #Y is under way (the LCD says so)
};

}  // namespace app

#endif  // FIRMWARE_APP_ITEM_EXECUTOR_H
