// Point generator: spline -> points -> planner -> coordinate ring (see point_generator.h).
#include "firmware/app/point_generator.h"

#include "firmware/core/divide.h"       // div_u32_by_u16
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
  split_.pieces_left = 0;
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
  split_.pieces_left = 0;
  const core::GeometryError e = walker_.begin(spline, settings_);
  active_ = e == core::GeometryError::kOk;
  return e;
}

// Splits the chord from_um -> p into n = ceil(span / max_step) pieces (span: the larger
// axis difference; the Chebyshev distance is within sqrt(2) of the length, good enough to
// bound the spacing). Once per chord: two or three 32/16 divisions, none per piece.
void PointGenerator::begin_split(const int32_t from_um[3], const core::PointUm& p) {
  const int32_t d[2] = {p.x_um - from_um[0], p.y_um - from_um[1]};
  const uint32_t ad[2] = {core::abs_u32(d[0]), core::abs_u32(d[1])};
  const uint32_t span = ad[0] > ad[1] ? ad[0] : ad[1];
  uint32_t n = 1;
  if (max_step_um_ != 0 && span > max_step_um_) {
    uint16_t rest = 0;
    n = core::div_u32_by_u16(span, max_step_um_, &rest);
    if (rest != 0) ++n;
  }
  split_.pieces = n;
  split_.pieces_left = n;
  const int32_t chord_um[3] = {d[0], d[1], z_um_ - from_um[2]};
  // n > 1: the chord is longer than the step, so not zero.
  if (n > 1) unit_direction_q14(chord_um, split_.dir_q14);
  for (uint8_t i = 0; i < 2; ++i) {
    uint32_t q;
    uint32_t r;
    if (n <= 0xFFFFUL) {
      uint16_t r16 = 0;
      q = core::div_u32_by_u16(ad[i], (uint16_t)n, &r16);
      r = r16;
    } else {  // over 65 535 pieces: a step under 31 um on a chord of metres
      q = ad[i] / n;
      r = ad[i] - q * n;
    }
    split_.step_um[i] = d[i] < 0 ? -(int32_t)q : (int32_t)q;
    split_.unit[i] = (int8_t)(d[i] < 0 ? -1 : 1);
    split_.frac[i] = r;
    split_.acc[i] = n >> 1;  // rounds each piece's end to the nearest micrometre
  }
}

// Pushes p, split into pieces no longer than the maximum step. False when the ring filled
// up; the remainder is pushed on the next call with the same p (split_ remembers where).
bool PointGenerator::push_point(Planner* planner, CoordinateRing* ring, const core::PointUm& p,
                                uint8_t flags) {
  if (split_.pieces_left == 0) begin_split(planner->last_um(), p);
  while (split_.pieces_left > 1) {
    const int32_t* last = planner->last_um();
    int32_t target[3] = {last[0], last[1], z_um_};
    uint32_t acc[2];
    for (uint8_t i = 0; i < 2; ++i) {
      acc[i] = split_.acc[i] + split_.frac[i];  // < 2 n
      target[i] += split_.step_um[i];
      if (acc[i] >= split_.pieces) {
        acc[i] -= split_.pieces;
        target[i] += split_.unit[i];
      }
    }
    if (!planner->push(ring, target, feed_um_s_, 0, tag_, split_.dir_q14)) return false;
    split_.acc[0] = acc[0];
    split_.acc[1] = acc[1];
    --split_.pieces_left;
  }
  // The last piece ends on p itself, with p's flags.
  const int32_t target[3] = {p.x_um, p.y_um, z_um_};
  const int16_t* dir = split_.pieces > 1 ? split_.dir_q14 : 0;
  if (!planner->push(ring, target, feed_um_s_, flags, tag_, dir)) return false;
  split_.pieces_left = 0;
  return true;
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
