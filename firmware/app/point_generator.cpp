// Point generator: spline -> points -> planner -> coordinate ring (see point_generator.h).
#include "firmware/app/point_generator.h"

#include <string.h>  // memset

namespace app {

// The walker constructs itself; every member after it is plain data and starts at zero
// (no maximum step, idle, nothing pending): one memset from settings_ to the end rather
// than a store per member (-0.1 kB on the AVR proxy), then the default settings.
PointGenerator::PointGenerator() {
  char* const from = reinterpret_cast<char*>(&settings_);
  memset(from, 0, (size_t)(reinterpret_cast<char*>(this + 1) - from));
  settings_ = core::default_step_settings();
}

void PointGenerator::set_resolution(uint16_t max_step_um, uint16_t chord_tolerance_um) {
  max_step_um_ = max_step_um;
  settings_.mode = core::StepMode::kAdaptive;
  settings_.chord_tolerance_um = chord_tolerance_um;
}

core::GeometryError PointGenerator::begin(const core::Spline* spline, uint16_t feed_um_s,
                                          int32_t z_um, uint16_t tag, int32_t tool_offset_um,
                                          uint16_t first_point) {
  settings_.tool_offset_um = tool_offset_um;  // this spline's (its #B); 0 = tool centre on it
  feed_um_s_ = feed_um_s;
  z_um_ = z_um;
  tag_ = tag;
  point_index_ = 0;
  first_point_ = first_point;
  have_pending_ = false;
  const core::GeometryError e = walker_.begin(spline, settings_);
  active_ = e == core::GeometryError::kOk;
  return e;
}

// Pushes p (at the spline's height); the planner splits the chord from the last point into
// pieces no longer than the maximum step. False when the ring filled up; the planner goes
// on with the remainder on the next call with the same p.
inline bool PointGenerator::push_point(Planner* planner, CoordinateRing* ring,
                                       const core::PointUm& p, uint8_t flags) {
  const int32_t target[3] = {p.x_um, p.y_um, z_um_};
  return planner->push(ring, target, feed_um_s_, flags, tag_, max_step_um_);
}

GenStatus PointGenerator::run(Planner* planner, CoordinateRing* ring, const int32_t travel_um[2],
                              uint8_t max_points) {
  if (!active_) return GenStatus::kDone;
  for (uint8_t n = 0; n < max_points; ++n) {
    if (!have_pending_) {
      if (!walker_.next(&pending_)) {
        active_ = false;
        if (walker_.error() != core::GeometryError::kOk) return GenStatus::kFailed;
        // The curve ended: the item's end marker sits on the last point.
        if (!planner->push(ring, planner->last_um(), feed_um_s_, kPointEndOfItem, tag_)) {
          active_ = true;  // retry the marker next time
          have_pending_ = false;
          return GenStatus::kMore;
        }
        return GenStatus::kDone;
      }
      if (pending_.x_um > travel_um[0] || pending_.x_um < -travel_um[0] ||
          pending_.y_um > travel_um[1] || pending_.y_um < -travel_um[1]) {
        active_ = false;
        return GenStatus::kOutside;
      }
      if (point_index_ < first_point_) {
        ++point_index_;  // resume: walked, not moved to
        continue;
      }
      have_pending_ = true;
    }
    // The walker's point itself (not a piece of its split chord) is a curve point: the tick
    // counts those, which is how the status says how far along a curve the tool got.
    if (!push_point(planner, ring, pending_, kPointCurvePoint)) return GenStatus::kMore;
    have_pending_ = false;
    if (point_index_ < 0xFFFFU) ++point_index_;
  }
  return GenStatus::kMore;
}

}  // namespace app
