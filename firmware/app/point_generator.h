// Point generator of the background loop: steps a stored spline through the core (De Boor,
// adaptive chord tolerance) and hands each point to the planner, which splits chords longer
// than the #U maximum step and publishes the pieces into the coordinate ring. Bounded work per
// call.
#ifndef FIRMWARE_APP_POINT_GENERATOR_H
#define FIRMWARE_APP_POINT_GENERATOR_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/app/coordinate_ring.h"  // CoordinateRing
#include "firmware/app/planner.h"          // Planner
#include "firmware/core/curve_walker.h"    // CurveWalker, StepSettings

namespace app {

enum class GenStatus : uint8_t {
  kMore = 0,    // call again (ring full or work budget used)
  kDone = 1,    // every point of the spline is in the ring (last one flagged)
  kFailed = 2,  // the core stopped (error()); points so far are in the ring
  kOutside = 3  // a generated point left the travel: nothing more pushed
};

class PointGenerator {
 public:
  PointGenerator();
  // Default: adaptive, 5 um chord tolerance, no maximum step.
  void set_resolution(uint16_t max_step_um, uint16_t chord_tolerance_um);
  // Starts a spline at feed, at height z_um; points carry tag. tool_offset_um: the tool
  // centre runs this far from the curve (> 0 left of travel, < 0 right, 0 on it).
  // first_point (resume): the curve points before it are walked as usual but not pushed,
  // so the points from it on are exactly those of a run from the start; the tool goes
  // straight from where it stands to point first_point.
  core::GeometryError begin(const core::Spline* spline, uint16_t feed_um_s, int32_t z_um,
                            uint16_t tag, int32_t tool_offset_um, uint16_t first_point);
  // Pushes up to max_points points; travel_um: allowed |x|, |y|.
  GenStatus run(Planner* planner, CoordinateRing* ring, const int32_t travel_um[2],
                uint8_t max_points);
  core::GeometryError error() const { return walker_.error(); }
  bool active() const { return active_; }
  void stop() { active_ = false; }

 private:
  bool push_point(Planner* planner, CoordinateRing* ring, const core::PointUm& p, uint8_t flags);

  core::CurveWalker walker_;
  core::StepSettings settings_;
  uint16_t max_step_um_;
  uint16_t feed_um_s_;
  int32_t z_um_;
  uint16_t tag_;
  uint16_t point_index_;   // curve points produced so far
  uint16_t first_point_;   // points before this one are skipped
  core::PointUm pending_;  // point produced but not yet pushed (ring was full)
  bool have_pending_;
  bool active_;
};

}  // namespace app

#endif  // FIRMWARE_APP_POINT_GENERATOR_H
