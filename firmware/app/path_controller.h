// The 1 ms path controller: actual position in, three native velocities out. Points the
// velocity at the current target, scales it by the planned speed, and takes the next target
// from the coordinate ring inside the capture radius. Fixed point only, no I/O, never waits.
#ifndef FIRMWARE_APP_PATH_CONTROLLER_H
#define FIRMWARE_APP_PATH_CONTROLLER_H

#include <stdint.h>  // int32_t, int16_t

#include "firmware/app/axis_scaling.h"     // AxisScaling
#include "firmware/app/coordinate_ring.h"  // CoordinateRing, PlanEntry

namespace app {

class PathController {
 public:
  PathController();
  void init(const AxisScaling& scaling);

  // One control step. pos_usteps: x_actual of X, Y, Z. v_units: v_target to write.
  void tick(const int32_t pos_usteps[config::kAxisCount], CoordinateRing* ring,
            int16_t v_units[config::kAxisCount]);

  // Feed hold: decelerate along the path to rest (true) or go on (false).
  void set_hold(bool hold) { hold_ = hold; }
  // Feed override in percent (10..200 accepted; others clamped).
  void set_override_percent(uint8_t percent);
  // Forgets the target and everything buffered (after a stop, zeroing or an alarm).
  void flush(CoordinateRing* ring);
  // Stops the commanded speed at once (alarm); velocities of the next tick are zero.
  void stop_now();

  // Commanded path speed, um/s.
  uint16_t speed_um_s() const { return speed_um_s_; }
  // Stopped: speed zero (at the last target, or held).
  bool at_rest() const { return speed_um_s_ == 0; }
  // Stopped on the last buffered target with nothing more to do.
  bool finished() const { return !have_target_ || arrived_; }
  bool holding() const { return hold_; }
  // Ring entries flagged kPointEndOfItem that were reached (wraps at 2^16).
  uint16_t items_done() const { return items_done_; }
  // Curve points (kPointCurvePoint) reached in the item being worked on, and whether that
  // item has a target yet; the stopped_ pair: their values when flush() dropped the ring.
  uint16_t item_points() const { return item_points_; }
  bool item_started() const { return item_started_; }
  uint16_t stopped_points() const { return stopped_points_; }
  bool stopped_started() const { return stopped_started_; }
  // Flags of the current target (0 without one).
  uint8_t current_flags() const { return have_target_ ? cur_.flags : 0; }

 private:
  // Where the current target lies from the tool: the direction in um * 2^fine, its squared
  // length, len in um = |dir| * 2^len_shift, and dir projected on the segment, * 2^14.
  struct Aim {
    int16_t dir[3];
    uint32_t sum_sq;
    int8_t len_shift;
    int32_t along;
  };
  bool take_target(CoordinateRing* ring);
  void aim_at_target(const int32_t pos_usteps[config::kAxisCount], uint8_t fine, Aim* aim) const;
  uint16_t ramp_speed(uint32_t len_um, const PlanEntry* next) const;
  uint16_t approach_end(uint16_t v, uint32_t len_q4);
  void take_popped();
  void leave_target();
  uint16_t cruise_of(const PlanEntry& e) const;
  void output(const int16_t dir[3], uint16_t len, int16_t v_units[3]);

  AxisScaling scaling_;
  PlanEntry cur_;
  int32_t residue_q8_[config::kAxisCount];  // velocity quantisation carried to the next tick
  uint16_t speed_um_s_;
  uint16_t items_done_;
  uint16_t item_points_;
  bool item_started_;
  uint16_t stopped_points_;
  bool stopped_started_;
  bool new_item_;         // the next target taken begins an item (after a flush)
  uint16_t override_q8_;  // override as a factor, 256 = 100 %
  uint8_t override_percent_;
  bool have_target_;
  bool arrived_;
  bool hold_;
};

// Arrival window at the end of the buffered path (1 um, in 1/16 um).
static const uint32_t kArriveQ4 = 16;

}  // namespace app

#endif  // FIRMWARE_APP_PATH_CONTROLLER_H
