// Look-ahead planner of the background loop: turns target points into planned ring entries
// (segment length and direction, corner speed, capture radius) and re-plans the buffered
// path backward so the path controller can always stop at the end of what is buffered.
#ifndef FIRMWARE_APP_PLANNER_H
#define FIRMWARE_APP_PLANNER_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/app/axis_scaling.h"     // AxisScaling
#include "firmware/app/coordinate_ring.h"  // CoordinateRing, PlanEntry

namespace app {

struct PlannerSettings {
  uint16_t capture_radius_um;     // largest target switch distance (config, 10 um)
  uint16_t corner_tolerance_um;   // path error allowed from the ramp lag at a corner
  uint16_t cut_tolerance_um;      // path error allowed from switching targets early
  uint16_t max_override_percent;  // plan for feeds up to this override
};

// Defaults: capture 10 um, corner 4 um, cut 2 um, override up to 200 %.
PlannerSettings default_planner_settings(uint16_t capture_radius_um);

// Speed reachable at the start of a segment of length_um that must end at exit_um_s,
// decelerating at accel (um/s per ms): sqrt(exit^2 + 2 a L), saturated at 32767.
uint16_t reach_speed_um_s(uint16_t exit_um_s, uint16_t accel_um_s_per_ms, uint32_t length_um);
// The same, but at most cap_um_s; when the result reaches the cap no square root is taken
// (the tick's common case: not on a braking curve).
uint16_t reach_speed_capped_um_s(uint16_t exit_um_s, uint16_t accel_um_s_per_ms, uint32_t length_um,
                                 uint16_t cap_um_s);

// Unit vector of d_um in Q14 (16384 = 1); false (and dir_q14 untouched) when d_um is zero.
bool unit_direction_q14(const int32_t d_um[config::kAxisCount],
                        int16_t dir_q14[config::kAxisCount]);

class Planner {
 public:
  Planner();
  void init(const AxisScaling& scaling, const PlannerSettings& settings);
  // The path starts here (machine position after boot, zeroing, abort or alarm).
  void set_origin(const int32_t at_um[config::kAxisCount]);
  // Plans the segment from the last point to target and publishes it. False when the ring
  // is full (nothing changed: call again later). line_dir_q14 (or 0): the unit direction of
  // the straight line the segment is a piece of (a chord split at the #U maximum step); it
  // stands for the piece's own, which the rounding of its ends to micrometres tilts (by up
  // to 45 degrees for 1 um pieces), so that the pieces of a line meet without turns.
  bool push(CoordinateRing* ring, const int32_t target_um[config::kAxisCount], uint16_t feed_um_s,
            uint8_t flags, uint16_t tag, const int16_t* line_dir_q14 = 0);
  // Where the last pushed segment ends.
  const int32_t* last_um() const { return last_um_; }

 private:
  void fill_segment(PlanEntry* e, const int32_t target_um[config::kAxisCount],
                    const int16_t* line_dir_q14);
  uint16_t corner_speed(const int16_t in_q14[3], const int16_t out_q14[3], int32_t omc_q14,
                        uint32_t sin_half_q14) const;
  uint16_t curve_speed(const int16_t in_q14[3], const int16_t out_q14[3], uint32_t sin_half_q14,
                       uint32_t in_um, uint32_t out_um) const;
  uint16_t capture_for(const int16_t in_q14[3], const int16_t out_q14[3]) const;
  void replan(CoordinateRing* ring);

  AxisScaling scaling_;
  PlannerSettings settings_;
  int32_t last_um_[config::kAxisCount];
  int16_t last_dir_q14_[config::kAxisCount];
  uint16_t last_cruise_um_s_;
  uint32_t last_length_um_;  // of the last segment with a length (curve speed)
  uint16_t normal_accel_um_s_per_ms_[config::kAxisCount];  // sqrt(chip^2 - plan^2), init()
  bool have_dir_;
};

}  // namespace app

#endif  // FIRMWARE_APP_PLANNER_H
