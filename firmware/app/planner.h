// Look-ahead planner of the background loop: turns target points into planned ring entries
// (segment length and direction, corner speed, capture radius) and re-plans the buffered
// path backward so the path controller can always stop at the end of what is buffered.
#ifndef FIRMWARE_APP_PLANNER_H
#define FIRMWARE_APP_PLANNER_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/app/axis_scaling.h"     // AxisScaling
#include "firmware/app/coordinate_ring.h"  // CoordinateRing, PlanEntry
#include "firmware/core/height_map.h"      // HeightMap

namespace app {

struct PlannerSettings {
  uint16_t capture_radius_um;     // largest target switch distance (config, 10 um)
  uint16_t corner_tolerance_um;   // path error allowed from the ramp lag at a corner
  uint16_t cut_tolerance_um;      // path error allowed from switching targets early
  uint16_t max_override_percent;  // plan for feeds up to this override
};

// Cutting segments are split into pieces at most this long (X/Y) while a height map is on.
static const uint16_t kFollowStepUm = 1000;

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
  // The path starts here (machine position after boot, zeroing, abort or alarm). With a
  // height map the planned Z there is the machine Z less the offset push() would add.
  void set_origin(const int32_t at_um[config::kAxisCount]);
  // The height map the targets follow (0: none; it is used while it is active). push() adds
  // its offset to the Z of every target: a target at or below the work surface (planned Z
  // <= 0, cutting) gets the interpolated surface height there, one above it (travel) the
  // map's highest height, so travel keeps its clearance over the highest probed point; a
  // cutting segment is cut into pieces of at most kFollowStepUm so Z follows the surface
  // between its ends. last_um() stays in planned coordinates.
  void set_height_map(core::HeightMap* map) { map_ = map; }
  // A zero-length point where the last segment ends (an item's end marker): nothing moves
  // and the planned position stays, so a height map changed just before applies from the
  // next target pushed on (its planned point plus the new offset), never on the spot.
  bool push_standing(CoordinateRing* ring, uint16_t feed_um_s, uint8_t flags, uint16_t tag);
  // push() without the map's offset: target is a machine position (the probe's moves).
  bool push_machine(CoordinateRing* ring, const int32_t target_um[config::kAxisCount],
                    uint16_t feed_um_s, uint8_t flags, uint16_t tag);
  // Plans the segment from the last point to target and publishes it. False when the ring
  // is full (call again later with the same target: the pieces pushed so far stay).
  // max_step_um (0: none): the segment is cut into equal pieces at most this long (on the
  // larger of X and Y) laid on the line, every piece's end within half a micrometre of it;
  // the pieces carry the line's direction instead of their own, which the rounding of
  // their ends to micrometres tilts (by up to 45 degrees for 1 um pieces), so that they
  // meet without turns. Only the last piece carries flags (the others keep kPointRapid).
  bool push(CoordinateRing* ring, const int32_t target_um[config::kAxisCount], uint16_t feed_um_s,
            uint8_t flags, uint16_t tag, uint16_t max_step_um = 0);
  // Where the last target pushed whole ends, planned (before the height map's offset).
  const int32_t* last_um() const { return planned_um_; }
  // Where the last pushed segment or piece ends, as the machine goes there (with the offset).
  const int32_t* machine_um() const { return last_um_; }

 private:
  void fill_segment(PlanEntry* e, const int32_t target_um[config::kAxisCount],
                    const int16_t* line_dir_q14);
  // axes: bit i set when axis i takes part in the turn (involved_axes in planner.cpp).
  uint16_t corner_speed(uint8_t axes, int32_t omc_q14, uint32_t sin_half_q14) const;
  uint16_t curve_speed(uint8_t axes, uint32_t sin_half_q14, uint32_t in_um, uint32_t out_um) const;
  uint16_t capture_for(const int16_t in_q14[3], const int16_t out_q14[3]) const;
  void replan(CoordinateRing* ring);
  bool push_segment(CoordinateRing* ring, const int32_t target_um[config::kAxisCount],
                    uint16_t feed_um_s, uint8_t flags, uint16_t tag, const int16_t* line_dir_q14);
  void set_planned_from_machine();
  int32_t offset_at(const int32_t planned_um[config::kAxisCount]);
  void begin_split(const int32_t target_um[config::kAxisCount], uint16_t max_step_um);

  // The segment being pushed in pieces (the #U maximum step, the height map's follow
  // step): a DDA from planned_um_ (piece k ends at from + round(k d / n)), so every piece
  // ends within half a micrometre of the line, however many pieces there are. Stepping
  // from each piece's end toward the target instead lets the rounding of every piece add
  // up into a bend off the line.
  struct LineAxis {
    int32_t to_um;    // the target it was set up for
    int32_t at_um;    // end of the last piece pushed
    int32_t step_um;  // d / n toward zero
    uint32_t frac;    // |d| mod n
    uint32_t acc;     // Bresenham error term, < n
    int8_t unit;      // sign of d: what a carry adds
  };
  struct LineSplit {
    LineAxis axis[config::kAxisCount];    // one record per axis: the loops walk a pointer
    uint32_t pieces;                      // n
    uint32_t left;                        // pieces not pushed yet; 0: no split set up
    int16_t dir_q14[config::kAxisCount];  // of the whole line, when on_line
    bool on_line;                         // split at max_step_um: pieces carry dir_q14
  };

  AxisScaling scaling_;
  PlannerSettings settings_;
  int32_t last_um_[config::kAxisCount];     // machine position the last segment ends at
  int32_t planned_um_[config::kAxisCount];  // the same before the map's offset
  core::HeightMap* map_;
  LineSplit split_;
  int16_t last_dir_q14_[config::kAxisCount];
  uint16_t last_cruise_um_s_;
  uint32_t last_length_um_;  // of the last segment with a length (curve speed)
  int16_t last_turn_q14_;    // sin(theta/2) at its start, signed as the turn (jogs)
  uint16_t normal_accel_um_s_per_ms_[config::kAxisCount];  // sqrt(chip^2 - plan^2), init()
  bool have_dir_;
};

}  // namespace app

#endif  // FIRMWARE_APP_PLANNER_H
