// Point generator: spline -> points -> planner -> coordinate ring (see point_generator.h).
#include "firmware/app/point_generator.h"

#include "firmware/core/fixed_point.h"  // abs_u32

namespace app {

PointGenerator::PointGenerator()
    : max_step_um_(0),
      feed_um_s_(0),
      z_um_(0),
      tag_(0),
      point_index_(0),
      first_point_(0),
      have_pending_(false),
      pending_is_last_(false),
      active_(false) {
  settings_ = core::default_step_settings();
  pending_.x_um = 0;
  pending_.y_um = 0;
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
  pending_is_last_ = false;
  const core::GeometryError e = walker_.begin(spline, settings_);
  active_ = e == core::GeometryError::kOk;
  return e;
}

// Pushes p, split into pieces no longer than the maximum step. False when the ring filled
// up; the remainder is pushed on the next call (the planner remembers where it is).
bool PointGenerator::push_point(Planner* planner, CoordinateRing* ring, const core::PointUm& p,
                                uint8_t flags) {
  for (;;) {
    const int32_t* last = planner->last_um();
    const int32_t dx = p.x_um - last[0];
    const int32_t dy = p.y_um - last[1];
    const uint32_t span =
        core::abs_u32(dx) > core::abs_u32(dy) ? core::abs_u32(dx) : core::abs_u32(dy);
    int32_t target[3] = {p.x_um, p.y_um, z_um_};
    uint8_t f = flags;
    // Chebyshev distance is within sqrt(2) of the length: good enough to bound the spacing.
    if (max_step_um_ != 0 && span > max_step_um_) {
      const uint32_t pieces = (span + max_step_um_ - 1U) / max_step_um_;
      target[0] = last[0] + dx / (int32_t)pieces;
      target[1] = last[1] + dy / (int32_t)pieces;
      f = 0;
    }
    if (!planner->push(ring, target, feed_um_s_, f, tag_)) return false;
    if (target[0] == p.x_um && target[1] == p.y_um) return true;
  }
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
        const int32_t* last = planner->last_um();
        const int32_t at[3] = {last[0], last[1], last[2]};
        if (!planner->push(ring, at, feed_um_s_, kPointEndOfItem, tag_)) {
          active_ = true;  // retry the marker next time
          have_pending_ = false;
          pending_is_last_ = true;
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
