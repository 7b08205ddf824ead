// The 1 ms path controller (see path_controller.h and docs/firmware.md "The tick").
#include "firmware/app/path_controller.h"

#include "firmware/app/planner.h"  // reach_speed_um_s
#include "firmware/app/vector3.h"  // normalise3, length3, scale_length_q4

namespace app {

namespace {

const uint8_t kMaxCapturesPerTick = 4;  // bounds the work when several points are passed

// Sum of products of a 15-bit vector and a Q14 unit vector (< 2^31); its sign matters.
int32_t dot(const int16_t a[3], const int16_t b[3]) {
  return (int32_t)a[0] * b[0] + (int32_t)a[1] * b[1] + (int32_t)a[2] * b[2];
}

// Micrometres covered in one millisecond at v um/s: v / 1000 as a multiply and a shift
// (1049 / 2^20 = 1.0004e-3).
uint32_t um_per_tick(uint16_t v_um_s) {
  return ((uint32_t)v_um_s * 1049UL) >> 20;
}

}  // namespace

PathController::PathController()
    : speed_um_s_(0),
      items_done_(0),
      override_q8_(256),
      override_percent_(100),
      have_target_(false),
      arrived_(false),
      hold_(false) {
  for (uint8_t i = 0; i < config::kAxisCount; ++i) {
    target_usteps_[i] = 0;
    residue_q8_[i] = 0;
  }
  cur_.tag = 0;
}

void PathController::init(const AxisScaling& scaling) {
  scaling_ = scaling;
  have_target_ = false;
  arrived_ = false;
  speed_um_s_ = 0;
}

void PathController::set_override_percent(uint8_t percent) {
  if (percent < 10) percent = 10;
  if (percent > 200) percent = 200;
  override_percent_ = percent;
  override_q8_ = (uint16_t)(((uint16_t)percent * 256U + 50U) / 100U);  // once, not per tick
}

void PathController::flush(CoordinateRing* ring) {
  ring->clear();
  have_target_ = false;
  arrived_ = false;
  speed_um_s_ = 0;
}

void PathController::stop_now() {
  speed_um_s_ = 0;
  for (uint8_t i = 0; i < config::kAxisCount; ++i) residue_q8_[i] = 0;
}

// Makes e the current target (microsteps computed once here, not every tick).
void PathController::take(const PlanEntry& e) {
  cur_ = e;
  for (uint8_t i = 0; i < config::kAxisCount; ++i) {
    target_usteps_[i] = um_to_usteps(scaling_, i, e.target_um[i]);
  }
  have_target_ = true;
  arrived_ = false;
}

// The current target is done (passed or reached): count finished items.
void PathController::leave_target() {
  if (cur_.flags & kPointEndOfItem) ++items_done_;
  cur_.flags = (uint8_t)(cur_.flags & ~kPointEndOfItem);
}

// Feed times override, within the axis limits of the segment.
uint16_t PathController::cruise_of(const PlanEntry& e) const {
  // Rapids run at the machine's rapid speed whatever the override (docs/protocol.md #F).
  uint32_t v = e.feed_um_s;
  if (!(e.flags & kPointRapid)) v = (v * override_q8_) >> 8;
  if (v > e.cruise_max_um_s) v = e.cruise_max_um_s;
  return (uint16_t)v;
}

void PathController::tick(const int32_t pos_usteps[config::kAxisCount], CoordinateRing* ring,
                          int16_t v_units[config::kAxisCount]) {
  PlanEntry next_copy;
  if (!have_target_) {
    if (!ring->pop(&next_copy)) {
      speed_um_s_ = 0;
      output(0, 0, v_units);
      return;
    }
    take(next_copy);
  }
  int16_t dir_um[3];
  uint16_t len = 0;
  uint32_t len_q4 = 0;
  const PlanEntry* next = 0;
  for (uint8_t captures = 0;; ++captures) {
    int32_t d[3];
    for (uint8_t i = 0; i < 3; ++i) d[i] = target_usteps_[i] - pos_usteps[i];
    int16_t n[3];
    int8_t shift;
    normalise3(d, n, &shift);
    for (uint8_t i = 0; i < 3; ++i) {
      dir_um[i] = (int16_t)(((int32_t)n[i] * scaling_.um_per_ustep_q[i]) >> scaling_.um_shift);
    }
    len = length3(dir_um);
    len_q4 = scale_length_q4(len, shift);
    next = ring->front();
    if (next == 0 || captures >= kMaxCapturesPerTick) break;
    // Switch early by the distance of one tick as well, so no target is jumped over.
    uint32_t capture_um = cur_.capture_um;
    const uint32_t per_tick_um = um_per_tick(speed_um_s_) + 1U;
    if (per_tick_um > capture_um) capture_um = per_tick_um;
    const bool passed = cur_.length_um > 0 && dot(dir_um, cur_.dir_q14) < 0;
    if (len_q4 > (capture_um << 4) && !passed) break;
    leave_target();
    ring->pop(&next_copy);
    take(next_copy);
  }

  // Speed: accelerate toward the cruise speed, never above what still lets the machine
  // reach the next corner (or a stop at the end of the buffer) at the planned speed.
  const uint16_t cruise = hold_ ? 0 : cruise_of(cur_);
  uint16_t exit = 0;
  if (next != 0 && !hold_) {
    exit = next->entry_max_um_s;
    const uint16_t next_cruise = cruise_of(*next);
    if (next_cruise < exit) exit = next_cruise;
  }
  const uint32_t len_um = len_q4 >> 4;
  const uint32_t travel_um = um_per_tick(speed_um_s_);  // covered before the next tick
  const uint16_t a = cur_.accel_um_s_per_ms;
  uint16_t v = speed_um_s_;
  // The braking curve only matters below max(cruise, v): cap there to skip the root.
  const uint16_t allow = reach_speed_capped_um_s(
      exit, a, len_um > travel_um ? len_um - travel_um : 0, cruise > v ? cruise : v);
  const uint16_t goal = cruise < allow ? cruise : allow;
  if (goal > v) {
    v = (uint16_t)(goal - v > a ? v + a : goal);
  } else if (allow < v) {
    v = allow;  // on the braking curve
  } else {
    v = (uint16_t)(v - goal > a ? v - a : goal);
  }
  if (next == 0 && !hold_) {
    if (len_q4 <= kArriveQ4 && v <= a) {
      if (!arrived_) leave_target();
      arrived_ = true;
      v = 0;
    } else if (len_q4 <= kArriveQ4) {
      v = (uint16_t)(v - a);  // inside the window but still fast: one more ramp step
    } else {
      // Last micrometres: proportional approach (v = 256/s * distance) so the stop is
      // exact; never below min(p, a) so the approach cannot stall short of the target.
      // The approach slows by at most a per tick (no step the chip's ramp cannot follow);
      // the braking rule above already guarantees the stop, this only makes it gentle.
      const uint32_t p = len_q4 * 16U;
      if (p < v) v = (uint32_t)(v - p) > a ? (uint16_t)(v - a) : (uint16_t)p;
      const uint16_t floor_v = p < a ? (uint16_t)p : a;
      if (v < floor_v) v = floor_v;
    }
  }
  speed_um_s_ = v;
  output(v == 0 ? 0 : dir_um, len, v_units);
}

// Velocity vector of length speed along dir_um, in native units, with the quantisation
// residue of each axis carried to the next tick (keeps the mean direction exact).
void PathController::output(const int16_t dir_um[3], uint16_t len, int16_t v_units[3]) {
  // One division per tick: speed / length in Q13; each component is then a product.
  // |dir_i| <= len, so dir_i * scale <= speed * 2^13 < 2^28.
  const int32_t scale_q13 =
      (dir_um == 0 || len == 0) ? 0 : (int32_t)(((uint32_t)speed_um_s_ << 13) / len);
  for (uint8_t i = 0; i < config::kAxisCount; ++i) {
    if (scale_q13 == 0) {
      v_units[i] = 0;
      residue_q8_[i] = 0;
      continue;
    }
    const int32_t c_um_s = ((int32_t)dir_um[i] * scale_q13) >> 13;
    const int32_t units_q8 =
        (c_um_s * (int32_t)scaling_.units_per_um_s_q[i]) >> (scaling_.units_shift - 8);
    int32_t acc = residue_q8_[i] + units_q8;
    int32_t out = (acc + 128) >> 8;
    if (out > scaling_.max_units[i]) out = scaling_.max_units[i];
    if (out < -scaling_.max_units[i]) out = -scaling_.max_units[i];
    acc -= out * 256;
    if (acc > 256) acc = 256;
    if (acc < -256) acc = -256;
    residue_q8_[i] = acc;
    v_units[i] = (int16_t)out;
  }
}

}  // namespace app
