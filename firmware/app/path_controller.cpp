// The 1 ms path controller (see path_controller.h and docs/firmware.md "The tick").
#include "firmware/app/path_controller.h"

#include <string.h>  // memset

#include "firmware/app/planner.h"       // reach_speed_um_s
#include "firmware/app/vector3.h"       // normalise3, length3, scale_length_q4
#include "firmware/core/divide.h"       // div_u32_u16
#include "firmware/core/fixed_point.h"  // mul_s16_u16, high_half, asr32
#include "firmware/core/isqrt.h"        // isqrt32

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

// Every member zero (no target, standing), then the 100 % override: plain data, so one
// memset rather than a store per member.
PathController::PathController() {
  memset(static_cast<void*>(this), 0, sizeof *this);
  override_q8_ = 256;
  override_percent_ = 100;
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
  stopped_points_ = item_points_;  // where the dropped item got to, for the status
  stopped_started_ = item_started_;
  item_points_ = 0;
  item_started_ = false;
  have_target_ = false;
  arrived_ = false;
  speed_um_s_ = 0;
}

void PathController::stop_now() {
  speed_um_s_ = 0;
  for (uint8_t i = 0; i < config::kAxisCount; ++i) residue_q8_[i] = 0;
}

// cur_ was just popped from the ring: it is the target now (in microsteps already: the
// planner converted it in the background).
void PathController::take_popped() {
  item_started_ = true;
  have_target_ = true;
  arrived_ = false;
}

// The current target is done (passed or reached): count finished items and curve points.
void PathController::leave_target() {
  // Saturates: a curve of more points reports 65 535 from there on (the host then knows
  // only that the tool passed that point), never a count that wrapped to a small one.
  if ((cur_.flags & kPointCurvePoint) && item_points_ != 0xFFFFU) ++item_points_;
  if (cur_.flags & kPointEndOfItem) {
    ++items_done_;
    item_points_ = 0;
    item_started_ = false;
  }
  cur_.flags = (uint8_t)(cur_.flags & ~(kPointEndOfItem | kPointCurvePoint));
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
  if (!have_target_ && !take_target(ring)) {
    speed_um_s_ = 0;
    output(0, 0, v_units);
    return;
  }
  // Aims at the current target, and takes the next ones from the ring while the tool is
  // inside their capture radius (or past them).
  const uint8_t fine = scaling_.um_shift > 16 ? (uint8_t)(scaling_.um_shift - 16) : 0;
  const uint32_t per_tick_um = um_per_tick(speed_um_s_) + 1U;  // once: speed is fixed here
  Aim aim;
  const PlanEntry* next = 0;
  for (uint8_t captures = 0;; ++captures) {
    aim_at_target(pos_usteps, fine, &aim);
    next = ring->front();
    if (next == 0 || captures >= kMaxCapturesPerTick) break;
    // Switch early by the distance of one tick as well, so no target is jumped over.
    uint32_t capture_um = cur_.capture_um;
    if (per_tick_um > capture_um) capture_um = per_tick_um;
    const bool passed = cur_.length_um > 0 && aim.along < 0;
    // The capture test compares squares: only the target finally kept needs a root.
    if (!passed && length_q4_exceeds(aim.sum_sq, aim.len_shift, capture_um << 4)) break;
    leave_target();
    take_target(ring);  // front() was not null: this pops it, straight into the target
  }
  // The full root, not a Newton step from the projection on the segment (isqrt32_from was
  // ~160 cycles less at the worst tick, 374 B more flash on the AVR proxy).
  const uint16_t len = core::isqrt32(aim.sum_sq);
  const uint32_t len_q4 = scale_length_q4(len, aim.len_shift);
  uint16_t v = ramp_speed(len_q4 >> 4, next);
  if (next == 0 && !hold_) v = approach_end(v, len_q4);
  speed_um_s_ = v;
  output(v == 0 ? 0 : aim.dir, len, v_units);
}

// The next target from the ring, popped straight into cur_; false while it is empty. Out of
// line: the ring's pop is code once for both callers (once per target, not per tick).
__attribute__((noinline)) bool PathController::take_target(CoordinateRing* ring) {
  if (!ring->pop(&cur_)) return false;
  take_popped();
  return true;
}

// The direction to the current target in um * 2^fine: n * um_per_ustep / 2^16, rounded,
// keeps the fraction bits of the micrometre (um_shift >= 16). Rounded down to whole
// micrometres (~1 300 units for a 0.08 um microstep) it leaned a fixed way, and as the tick
// aims at the target every ms, a long slow move ran that angle times the distance off its
// line.
inline void PathController::aim_at_target(const int32_t pos_usteps[config::kAxisCount],
                                          uint8_t fine, Aim* aim) const {
  int32_t d[3];
  for (uint8_t i = 0; i < 3; ++i) d[i] = cur_.target_usteps[i] - pos_usteps[i];
  int16_t n[3];
  int8_t shift;
  normalise3(d, n, &shift);
  // n * um_per_ustep: a 16x16 product (|.| <= 32767 * 65535: + 2^15 cannot overflow),
  // rounded to its high half (a byte move).
  for (uint8_t i = 0; i < 3; ++i) {
    const int32_t p = core::mul_s16_u16(n[i], scaling_.um_per_ustep_q[i]);
    aim->dir[i] = scaling_.um_shift < 16 ? (int16_t)core::asr32(p, scaling_.um_shift)
                                         : core::high_half(p + 0x8000L);
  }
  aim->sum_sq = sum_squares3(aim->dir);
  aim->len_shift = (int8_t)(shift - fine);  // len in um = |dir| * 2^len_shift
  aim->along = dot(aim->dir, cur_.dir_q14);
}

// Speed: accelerate toward the cruise speed, never above what still lets the machine
// reach the next corner (or a stop at the end of the buffer) at the planned speed.
// A hold only lowers the cruise speed: the corner and end-of-buffer limits stay, so the
// tool slows at the planned rate along the buffered points (braking to the current target
// instead would drop the speed faster than the chip's ramps follow and leave the path).
inline uint16_t PathController::ramp_speed(uint32_t len_um, const PlanEntry* next) const {
  const uint16_t cruise = hold_ ? 0 : cruise_of(cur_);
  uint16_t exit = 0;
  if (next != 0) {
    exit = next->entry_max_um_s;
    const uint16_t next_cruise = cruise_of(*next);
    if (next_cruise < exit) exit = next_cruise;
  }
  const uint32_t travel_um = um_per_tick(speed_um_s_);  // covered before the next tick
  const uint16_t a = cur_.accel_um_s_per_ms;
  uint16_t v = speed_um_s_;
  // The braking curve only matters below max(cruise, v): cap there to skip the root.
  const uint16_t allow = reach_speed_capped_um_s(
      exit, a, len_um > travel_um ? len_um - travel_um : 0, cruise > v ? cruise : v);
  const uint16_t goal = cruise < allow ? cruise : allow;
  if (goal > v) return (uint16_t)(goal - v > a ? v + a : goal);
  if (allow < v) return allow;  // on the braking curve
  return (uint16_t)(v - goal > a ? v - a : goal);
}

// The last buffered target, not held: arrival inside the window, else the approach.
inline uint16_t PathController::approach_end(uint16_t v, uint32_t len_q4) {
  const uint16_t a = cur_.accel_um_s_per_ms;
  if (len_q4 <= kArriveQ4 && v <= a) {
    if (!arrived_) leave_target();
    arrived_ = true;
    return 0;
  }
  if (len_q4 <= kArriveQ4) return (uint16_t)(v - a);  // still fast: one more ramp step
  // Last micrometres: proportional approach (v = 256/s * distance) so the stop is
  // exact; never below min(p, a) so the approach cannot stall short of the target.
  // The approach slows by at most a per tick (no step the chip's ramp cannot follow);
  // the braking rule above already guarantees the stop, this only makes it gentle.
  const uint32_t p = len_q4 * 16U;
  if (p < v) v = (uint32_t)(v - p) > a ? (uint16_t)(v - a) : (uint16_t)p;
  const uint16_t floor_v = p < a ? (uint16_t)p : a;
  if (v < floor_v) v = floor_v;
  return v;
}

// Always inline: tick() is its one caller (-68 B on the AVR proxy).
// Velocity vector of length speed along dir (len = |dir|, any unit), in native units, with
// the quantisation residue of each axis carried to the next tick (keeps the mean direction
// exact).
inline __attribute__((always_inline)) void PathController::output(const int16_t dir[3],
                                                                  uint16_t len,
                                                                  int16_t v_units[3]) {
  // One 32/16 division per tick (DIV.UD on the dsPIC): scale = speed * 2^k / len < 2^16,
  // k = 13 unless len is short against the speed (then as many bits as fit; >= 2^15 of
  // them, so the scale keeps 15 significant bits). |dir_i| <= len, so each component
  // dir_i * scale >> k is at most the speed: a 16x16 product.
  uint16_t scale = 0;
  uint8_t k = 13;
  if (dir != 0 && len != 0) {
    uint32_t num = ((uint32_t)speed_um_s_ << 16) >> 3;  // speed * 2^13: byte move, 3 steps
    const uint32_t limit = (uint32_t)len << 16;
    while (k > 0 && num >= limit) {
      num >>= 1;
      --k;
    }
    if (num < limit) scale = core::div_u32_u16(num, len, 0);
  }
  for (uint8_t i = 0; i < config::kAxisCount; ++i) {
    if (scale == 0) {
      v_units[i] = 0;
      residue_q8_[i] = 0;
      continue;
    }
    // The axis speed c in um/s with 8 fraction bits (|c| <= speed < 2^15: < 2^23), then
    // c * units_per_um_s_q / 2^(units_shift - 8) as a 32x16 product (units_shift >= 16).
    // Rounded down to whole um/s, c leaned a fixed way like the direction above. An axis
    // that does not move (Z while cutting) skips the products: only its residue is carried.
    int32_t units_q8 = 0;
    if (dir[i] != 0) {
      const int32_t p = core::mul_s16_u16(dir[i], scale);  // c * 2^k
      const int32_t c_q8 = k >= 8 ? core::asr32(p, (uint8_t)(k - 8)) : p * (1L << (8 - k));
      const uint8_t us = scaling_.units_shift;
      units_q8 = core::asr32(core::mul_32x16_uq16(c_q8, scaling_.units_per_um_s_q[i]),
                             us > 16 ? (uint8_t)(us - 16) : 0);
    }
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
