// Spline slots for #B/#D (see spline_store.h).
#include "firmware/app/spline_store.h"

#include <string.h>  // memcpy

#include "firmware/protocol/compact_spline.h"  // unpack_compact
#include "firmware/protocol/contour_spline.h"  // unpack_contour, is_contour_shape

namespace app {

SplineStore::SplineStore() {
  clear();
}

void SplineStore::clear() {
  for (uint8_t i = 0; i < kSlots; ++i) {
    state_[i] = SlotState::kFree;
    controls_[i] = 0;
    knots_[i] = 0;
  }
  open_ = kSlots;
}

bool SplineStore::has_free_slot() const {
  for (uint8_t i = 0; i < kSlots; ++i) {
    if (state_[i] == SlotState::kFree) return true;
  }
  return false;
}

uint8_t SplineStore::free_slots() const {
  uint8_t n = 0;
  for (uint8_t i = 0; i < kSlots; ++i) {
    if (state_[i] == SlotState::kFree) ++n;
  }
  return n;
}

proto::ErrorCode SplineStore::begin(const proto::SplineHeaderCmd& h, uint8_t* slot) {
  if (h.degree < 1 || h.degree > core::kMaxDegree) return proto::ErrorCode::kFieldRange;
  if (h.control_count < (uint16_t)(h.degree + 1U) || h.control_count > core::kMaxControlPoints)
    return proto::ErrorCode::kFieldRange;
  if (h.knot_count != (uint16_t)(h.control_count + h.degree + 1U))
    return proto::ErrorCode::kFieldRange;
  if (h.feed_um_per_s == 0) return proto::ErrorCode::kFieldRange;
  uint8_t s = 0;
  while (s < kSlots && state_[s] != SlotState::kFree) ++s;
  if (s == kSlots) return proto::ErrorCode::kBusy;
  // A spline still open (its data never finished) is abandoned: the new #B replaces it.
  if (open_ < kSlots) state_[open_] = SlotState::kCancelled;
  core::Spline& sp = spline_[s];
  sp.degree = h.degree;
  sp.rational = h.rational;
  sp.control_count = h.control_count;
  sp.knot_count = h.knot_count;
  controls_[s] = 0;
  knots_[s] = 0;
  state_[s] = SlotState::kFilling;
  open_ = s;
  *slot = s;
  return proto::ErrorCode::kOk;
}

// Indices must continue exactly where the previous data frame stopped, within the header's
// counts.
proto::ErrorCode SplineStore::check_next(uint8_t control_index, uint8_t control_n,
                                         uint8_t knot_index, uint8_t knot_n) const {
  if (open_ >= kSlots) return proto::ErrorCode::kSplineSequence;
  const uint8_t s = open_;
  const core::Spline& sp = spline_[s];
  if (control_index != controls_[s] || knot_index != knots_[s])
    return proto::ErrorCode::kSplineSequence;
  if ((uint16_t)(controls_[s] + control_n) > sp.control_count ||
      (uint16_t)(knots_[s] + knot_n) > sp.knot_count)
    return proto::ErrorCode::kSplineSequence;
  return proto::ErrorCode::kOk;
}

// The n points from index `from` (written, not yet committed) inside the travel.
static bool inside_travel(const core::Spline& sp, uint16_t from, uint8_t n,
                          const int32_t travel_um[2]) {
  for (uint8_t i = 0; i < n; ++i) {
    const core::ControlPoint& p = sp.control[from + i];
    if (p.x_um > travel_um[0] || p.x_um < -travel_um[0] || p.y_um > travel_um[1] ||
        p.y_um < -travel_um[1])
      return false;
  }
  return true;
}

// Counts the frame's values as stored; when the spline is complete, validates it.
proto::ErrorCode SplineStore::commit(uint8_t control_n, uint8_t knot_n, uint8_t* detail,
                                     bool* completed) {
  const uint8_t s = open_;
  core::Spline& sp = spline_[s];
  controls_[s] = (uint16_t)(controls_[s] + control_n);
  knots_[s] = (uint16_t)(knots_[s] + knot_n);
  if (controls_[s] < sp.control_count || knots_[s] < sp.knot_count) return proto::ErrorCode::kOk;
  open_ = kSlots;
  *completed = true;
  const core::GeometryError g = core::validate_spline(sp);
  if (g != core::GeometryError::kOk) {
    state_[s] = SlotState::kCancelled;
    *detail = (uint8_t)g;
    return proto::ErrorCode::kGeometry;
  }
  state_[s] = SlotState::kReady;
  return proto::ErrorCode::kOk;
}

// commit() of the frame's points once they lie inside the travel.
proto::ErrorCode SplineStore::commit_inside(uint8_t control_index, uint8_t control_n,
                                            uint8_t knot_n, const int32_t travel_um[2],
                                            uint8_t* detail, bool* completed) {
  if (!inside_travel(spline_[open_], control_index, control_n, travel_um))
    return proto::ErrorCode::kOutOfTravel;
  return commit(control_n, knot_n, detail, completed);
}

proto::ErrorCode SplineStore::add(const proto::SplineDataCmd& d, const int32_t travel_um[2],
                                  uint8_t* detail, bool* completed) {
  *detail = 0;
  *completed = false;
  const proto::ErrorCode e = check_next(d.control_index, d.control_n, d.knot_index, d.knot_n);
  if (e != proto::ErrorCode::kOk) return e;
  // Written behind the stored values: only commit() makes them part of the spline.
  core::Spline& sp = spline_[open_];
  core::ControlPoint* const to = &sp.control[d.control_index];
  memcpy(to, d.control, d.control_n * sizeof d.control[0]);
  if (!sp.rational) {
    for (uint8_t i = 0; i < d.control_n; ++i) to[i].weight_q14 = core::kWeightOneQ14;
  }
  memcpy(&sp.knot[d.knot_index], d.knot, d.knot_n * sizeof d.knot[0]);
  return commit_inside(d.control_index, d.control_n, d.knot_n, travel_um, detail, completed);
}

// The values are unpacked behind the stored ones; only commit() makes them part of the
// spline, so a refused frame changes nothing.
proto::ErrorCode SplineStore::add_compact(const proto::SplineCompactCmd& d,
                                          const int32_t travel_um[2], uint8_t* detail,
                                          bool* completed) {
  *detail = 0;
  *completed = false;
  proto::ErrorCode e = check_next(d.control_index, d.control_n, d.knot_index, d.knot_n);
  if (e != proto::ErrorCode::kOk) return e;
  core::Spline& sp = spline_[open_];
  e = proto::unpack_compact(d, &sp);
  if (e != proto::ErrorCode::kOk) return e;
  return commit_inside(d.control_index, d.control_n, d.knot_n, travel_um, detail, completed);
}

proto::ErrorCode SplineStore::add_contour(const proto::SplineContourCmd& d,
                                          const int32_t travel_um[2], uint8_t* detail,
                                          bool* completed) {
  *detail = 0;
  *completed = false;
  proto::ErrorCode e = check_next(d.control_index, d.control_n, 0, 0);
  if (e != proto::ErrorCode::kOk) return e;
  core::Spline& sp = spline_[open_];
  if (!proto::is_contour_shape(sp) ||
      (d.control_index > 0 && sp.control[d.control_index - 1].weight_q14 != core::kWeightOneQ14))
    return proto::ErrorCode::kSplineSequence;
  e = proto::unpack_contour(d, &sp);
  if (e != proto::ErrorCode::kOk) return e;
  const bool last = (uint16_t)(d.control_index + d.control_n) == sp.control_count;
  return commit_inside(d.control_index, d.control_n, last ? (uint8_t)sp.knot_count : 0, travel_um,
                       detail, completed);
}

void SplineStore::release(uint8_t slot) {
  if (slot >= kSlots) return;
  if (open_ == slot) open_ = kSlots;
  state_[slot] = SlotState::kFree;
  controls_[slot] = 0;
  knots_[slot] = 0;
}

}  // namespace app
