// Look-ahead planner: segment geometry, corner speeds, capture radii, backward pass.
#include "firmware/app/planner.h"

#include <string.h>  // memcpy, memmove, memset

#include "firmware/app/vector3.h"       // normalise3, length3
#include "firmware/core/divide.h"       // div_u32_by_u16
#include "firmware/core/fixed_point.h"  // abs_u32
#include "firmware/core/isqrt.h"        // isqrt32

namespace app {

namespace {

const uint16_t kOneQ14 = 16384U;
const int16_t kInvolvedQ14 = 256;  // an axis moving more than 1/64 of the path counts
const uint16_t kMaxSpeed = 32767U;

uint16_t min16(uint16_t a, uint16_t b) {
  return a < b ? a : b;
}

// Q14 dot product of two unit vectors. Out of line: push_segment's corner and capture both
// take it (-28 B on the AVR proxy).
__attribute__((noinline)) int32_t dot_q14(const int16_t a[3], const int16_t b[3]) {
  return ((int32_t)a[0] * b[0] + (int32_t)a[1] * b[1] + (int32_t)a[2] * b[2]) >> 14;
}

// Bit i set when axis i moves more than kInvolvedQ14 in either direction (the axes whose
// limits a corner or a curve meets): once per push, for both speed limits.
uint8_t involved_axes(const int16_t in_q14[3], const int16_t out_q14[3]) {
  uint8_t mask = 0;
  for (uint8_t i = 3; i-- > 0;) {  // from Z down: bit 0 ends as X's (no variable shift)
    mask = (uint8_t)(mask << 1);
    if (in_q14[i] > kInvolvedQ14 || in_q14[i] < -kInvolvedQ14 || out_q14[i] > kInvolvedQ14 ||
        out_q14[i] < -kInvolvedQ14)
      mask = (uint8_t)(mask | 1U);
  }
  return mask;
}

// Normalises d (normalise3: n, *shift) and returns |n| (0 for a zero d); unless it is 0,
// writes line_dir_q14 (when given) or n / |n| in Q14 to dir_q14: |n_i| <= |n|, so each
// quotient is a 32/16 division on the magnitude (the same value as the signed quotient).
uint16_t unit_of(const int32_t d[3], const int16_t* line_dir_q14, int16_t dir_q14[3],
                 int8_t* shift) {
  int16_t n[3];
  normalise3(d, n, shift);
  const uint16_t len = length3(n);
  if (len == 0) return 0;
  for (uint8_t i = 0; i < 3; ++i) {
    if (line_dir_q14 != 0) {
      dir_q14[i] = line_dir_q14[i];
      continue;
    }
    const int16_t q = (int16_t)core::div_u32_u16(core::abs_u32(n[i]) << 14, len, 0);
    dir_q14[i] = n[i] < 0 ? (int16_t)-q : q;
  }
  return len;
}

}  // namespace

PlannerSettings default_planner_settings(uint16_t capture_radius_um) {
  PlannerSettings s;
  s.capture_radius_um = capture_radius_um;
  s.corner_tolerance_um = 4;
  s.cut_tolerance_um = 2;
  s.max_override_percent = 200;
  return s;
}

uint16_t reach_speed_um_s(uint16_t exit_um_s, uint16_t accel_um_s_per_ms, uint32_t length_um) {
  return reach_speed_capped_um_s(exit_um_s, accel_um_s_per_ms, length_um, kMaxSpeed);
}

uint16_t reach_speed_capped_um_s(uint16_t exit_um_s, uint16_t accel_um_s_per_ms, uint32_t length_um,
                                 uint16_t cap_um_s) {
  // v^2 = exit^2 + 2000 a L (a in um/s per ms). No division: a L >= 536870 means
  // 2000 a L >= 2^30 > 32767^2, i.e. beyond any speed; below that the sum fits 31 bits.
  const uint32_t kSaturateAL = 536870UL;
  if (cap_um_s > kMaxSpeed) cap_um_s = kMaxSpeed;
  if (length_um >= 65536UL && (accel_um_s_per_ms >= 9U || length_um >= kSaturateAL))
    return cap_um_s;
  const uint32_t a_l = (uint32_t)accel_um_s_per_ms * length_um;  // < 2^32 by the test above
  if (a_l >= kSaturateAL) return cap_um_s;
  const uint32_t v_sq = (uint32_t)exit_um_s * exit_um_s + a_l * 2000UL;
  // Most ticks are not limited by the braking curve: compare squares, skip the root.
  if (v_sq >= (uint32_t)cap_um_s * cap_um_s) return cap_um_s;
  return core::isqrt32(v_sq);  // < cap <= 32767
}

bool unit_direction_q14(const int32_t d_um[config::kAxisCount],
                        int16_t dir_q14[config::kAxisCount]) {
  int8_t shift;
  return unit_of(d_um, 0, dir_q14, &shift) != 0;
}

// Every member zero (no map, nothing planned), then the settings: plain data, so one
// memset rather than a store per member.
Planner::Planner() {
  memset(static_cast<void*>(this), 0, sizeof *this);
  settings_ = default_planner_settings(10);
}

void Planner::init(const AxisScaling& scaling, const PlannerSettings& settings) {
  scaling_ = scaling;
  settings_ = settings;
  have_dir_ = false;
  last_length_um_ = 0;
  // What each axis's ramp has beside the planned tangential acceleration (curve speed).
  for (uint8_t i = 0; i < config::kAxisCount; ++i) {
    const uint32_t chip = scaling.chip_accel_um_s_per_ms[i];
    const uint32_t plan = scaling.plan_accel_um_s_per_ms[i];
    normal_accel_um_s_per_ms_[i] =
        (uint16_t)(chip > plan ? core::isqrt32(chip * chip - plan * plan) : 0);
  }
}

void Planner::set_origin(const int32_t at_um[config::kAxisCount]) {
  memcpy(last_um_, at_um, sizeof last_um_);
  set_planned_from_machine();
  have_dir_ = false;
  last_cruise_um_s_ = 0;
  last_length_um_ = 0;
}

// fill_segment, corner_speed, curve_speed, capture_for and replan are inline: push_segment
// is the one caller of each (out of line, their prologues and calls were 0.4 kB on the AVR
// proxy).
// Length, direction, acceleration and cruise limit of the segment last -> target.
inline void Planner::fill_segment(PlanEntry* e, const int32_t target_um[config::kAxisCount],
                                  const int16_t* line_dir_q14) {
  int32_t d[3];
  for (uint8_t i = 0; i < 3; ++i) {
    e->target_usteps[i] = um_to_usteps(scaling_, i, target_um[i]);
    d[i] = target_um[i] - last_um_[i];
  }
  int8_t shift;
  const uint16_t len = unit_of(d, line_dir_q14, e->dir_q14, &shift);
  if (len == 0) {
    // Zero length: keep the previous direction so the corner logic sees no turn.
    for (uint8_t i = 0; i < 3; ++i) e->dir_q14[i] = last_dir_q14_[i];
    e->length_um = 0;
    e->cruise_max_um_s = last_cruise_um_s_ ? last_cruise_um_s_ : scaling_.max_speed_um_s[0];
    e->accel_um_s_per_ms = scaling_.plan_accel_um_s_per_ms[0];
    return;
  }
  const uint32_t len_q4 = scale_length_q4(len, shift);
  e->length_um = (len_q4 + 8) >> 4;
  uint16_t accel = 65535U;
  uint16_t cruise = kMaxSpeed;
  for (uint8_t i = 0; i < 3; ++i) {
    const int16_t c = e->dir_q14[i] < 0 ? (int16_t)-e->dir_q14[i] : e->dir_q14[i];
    if (c <= kInvolvedQ14) continue;
    accel = min16(accel, scaling_.plan_accel_um_s_per_ms[i]);
    // Path speed at which this axis reaches its own limit: vmax / |u_i|.
    const uint32_t v = (uint32_t)scaling_.max_speed_um_s[i] * kOneQ14 / (uint16_t)c;
    if (v < cruise) cruise = (uint16_t)v;
  }
  e->accel_um_s_per_ms = accel;
  e->cruise_max_um_s = cruise;
}

// Corner speed: the chip ramps each axis toward the new velocity, so a velocity step of |dv|
// leaves a path error of at most |dv|^2 / 2a; |dv| = 2 v sin(theta/2) gives
// v^2 <= a e / (1 - cos theta). Meanwhile the tick already speeds up along the new direction
// at the planned a_p, whose part along the step (u2 - u1) / |u2 - u1| is a_p sin(theta/2):
// the ramp absorbs the step at a = a_chip - a_p sin(theta/2) (a_chip on gentle turns, about
// a_chip - a_p at a reversal, where the tool nearly stops and then speeds up).
inline uint16_t Planner::corner_speed(uint8_t axes, int32_t omc_q14, uint32_t sin_half_q14) const {
  if (omc_q14 <= 0) return kMaxSpeed;
  uint32_t a_um_s2 = 0xFFFFFFFFUL;
  for (uint8_t i = 0; i < 3; ++i, axes = (uint8_t)(axes >> 1)) {
    if (!(axes & 1U)) continue;
    const uint32_t chip = scaling_.chip_accel_um_s_per_ms[i];
    const uint32_t taken = (scaling_.plan_accel_um_s_per_ms[i] * sin_half_q14) >> 14;
    const uint32_t a = 1000UL * (chip > taken ? chip - taken : 1);
    if (a < a_um_s2) a_um_s2 = a;
  }
  if (a_um_s2 == 0xFFFFFFFFUL) return kMaxSpeed;
  const uint32_t q = a_um_s2 * settings_.corner_tolerance_um / (uint32_t)omc_q14;
  if (q >= 65535UL) return kMaxSpeed;  // v^2 = q * 2^14 >= 2^30
  return core::isqrt32(q << 14);
}

// Curve speed: a chain of short segments turning by theta at each point is a curve of radius
// R = L / (2 sin(theta/2)) (L the shorter neighbour); going round it at v needs v^2 / R of
// acceleration for as long as the curve lasts, which each small corner alone does not see.
// The tick may speed up or slow down at the planned a_t meanwhile; the chip ramps each axis
// at a_chip, and a_t u + a_n n stays within it on every axis when a_n^2 + a_t^2 <= a_chip^2:
// v^2 <= R sqrt(a_chip^2 - a_t^2) (a_t = 3/4 a_chip by default: a_n = 0.66 a_chip).
inline uint16_t Planner::curve_speed(uint8_t axes, uint32_t sin_half_q14, uint32_t in_um,
                                     uint32_t out_um) const {
  if (sin_half_q14 == 0) return kMaxSpeed;
  uint16_t a = 65535U;
  for (uint8_t i = 0; i < 3; ++i, axes = (uint8_t)(axes >> 1)) {
    if (axes & 1U) a = min16(a, normal_accel_um_s_per_ms_[i]);
  }
  uint32_t len = in_um < out_um ? in_um : out_um;
  if (len > 65535UL) len = 65535UL;
  const uint32_t t = (uint32_t)a * len;           // um/s per ms * um, < 2^32
  if (t >= 4194304UL) return kMaxSpeed;           // t * 1000 * 2^14 / 2^15 > 2^30: no limit
  const uint32_t two_sin_q14 = sin_half_q14 * 2;  // 2 sin(theta/2), Q14, at most 2^15
  const uint32_t q = t * 1000UL / two_sin_q14;    // v^2 / 2^14 in um^2/s^2
  if (q >= 65536UL) return kMaxSpeed;
  return core::isqrt32(q << 14);
}

// Switching to the next target at distance r before a corner of turn theta cuts it by
// about r sin(theta) (r beyond 90 degrees): r = min(capture, cut / sin(theta)).
inline uint16_t Planner::capture_for(const int16_t in_q14[3], const int16_t out_q14[3]) const {
  const int32_t c = dot_q14(in_q14, out_q14);
  uint32_t sin_q14 = kOneQ14;
  if (c > 0) {
    const uint32_t cc = (uint32_t)(c > 16384 ? 16384 : c);
    sin_q14 = core::isqrt32((uint32_t)kOneQ14 * kOneQ14 - cc * cc);
  }
  uint32_t r = settings_.capture_radius_um;
  if (sin_q14 > 0) {
    const uint32_t r_cut = (uint32_t)settings_.cut_tolerance_um * kOneQ14 / sin_q14;
    if (r_cut < r) r = r_cut;
  }
  if (r < 1) r = 1;
  return (uint16_t)r;
}

// The planned position of the machine position last_um_: with the map on, a Z above the
// highest height by more than nothing is travel (its offset is that height), else the
// surface's offset where the tool stands comes off.
void Planner::set_planned_from_machine() {
  memcpy(planned_um_, last_um_, sizeof planned_um_);
  split_.left = 0;
  if (map_ == 0 || !map_->active()) return;
  const int32_t travel_z = last_um_[2] - map_->highest_um();
  planned_um_[2] =
      travel_z > 0 ? travel_z : last_um_[2] - map_->offset_um(last_um_[0], last_um_[1]);
}

// The map's offset for a planned point: the surface height under a cutting point, the
// highest height under a travel one.
int32_t Planner::offset_at(const int32_t planned_um[config::kAxisCount]) {
  if (planned_um[2] > 0) return map_->highest_um();
  return map_->offset_um(planned_um[0], planned_um[1]);
}

bool Planner::push(CoordinateRing* ring, const int32_t target_um[config::kAxisCount],
                   uint16_t feed_um_s, uint8_t flags, uint16_t tag, uint16_t max_step_um) {
  // The split under way goes on only for its own target (a loop: -24 B on the AVR proxy
  // against three unrolled 32-bit comparisons).
  bool same = split_.left != 0;
  for (uint8_t i = 0; i < 3 && same; ++i) same = split_.axis[i].to_um == target_um[i];
  if (!same) begin_split(target_um, max_step_um);
  const bool following = map_ != 0 && map_->active();
  const int16_t* dir = split_.on_line ? split_.dir_q14 : 0;
  // One loop for the pieces and the last one, which ends on the target itself with its
  // flags (one call of push_segment and offset_at instead of two each: -0.1 kB on the AVR
  // proxy).
  for (;;) {
    const bool last = split_.left <= 1;
    int32_t piece[3];
    for (uint8_t i = 0; i < 3; ++i) {
      const LineAxis& a = split_.axis[i];
      piece[i] = a.at_um + a.step_um;
      if (a.acc + a.frac >= split_.pieces) piece[i] += a.unit;  // acc + frac < 2 n
      if (last) piece[i] = target_um[i];
    }
    // The machine goes to the piece plus the map's offset (in place: a smaller frame).
    const int32_t offset_um = following ? offset_at(piece) : 0;
    piece[2] += offset_um;
    if (!push_segment(ring, piece, feed_um_s, last ? flags : (uint8_t)(flags & kPointRapid), tag,
                      dir))
      return false;
    if (last) break;
    piece[2] -= offset_um;
    for (uint8_t i = 0; i < 3; ++i) {  // the piece is pushed: the DDA steps on
      LineAxis& a = split_.axis[i];
      a.at_um = piece[i];
      a.acc += a.frac;
      if (a.acc >= split_.pieces) a.acc -= split_.pieces;
    }
    --split_.left;
  }
  split_.left = 0;
  memmove(planned_um_, target_um, sizeof planned_um_);  // a marker's target is last_um()
  return true;
}

bool Planner::push_machine(CoordinateRing* ring, const int32_t target_um[config::kAxisCount],
                           uint16_t feed_um_s, uint8_t flags, uint16_t tag) {
  if (!push_segment(ring, target_um, feed_um_s, flags, tag, 0)) return false;
  set_planned_from_machine();
  return true;
}

bool Planner::push_standing(CoordinateRing* ring, uint16_t feed_um_s, uint8_t flags, uint16_t tag) {
  // To last_um_ itself: push_segment reads the target before it writes last_um_ (the same).
  if (!push_segment(ring, last_um_, feed_um_s, flags, tag, 0)) return false;
  split_.left = 0;  // a split under way (of the old map) is over
  return true;
}

// Splits planned_um_ -> target into n = ceil(span / step) pieces, span the larger of the X
// and Y differences (within sqrt(2) of the length: good enough to bound the spacing). The
// step is max_step_um (0: none), and at most kFollowStepUm when a height map is followed
// and both ends cut (travel has one offset all along: nothing to follow). Once per
// segment: two or three 32/16 divisions, none per piece; nothing divided when n is 1 (the
// common case: spline points closer than the step).
// Always inline: push() is its one caller (-0.1 kB on the AVR proxy; -Os keeps it apart).
inline __attribute__((always_inline)) void Planner::begin_split(
    const int32_t target_um[config::kAxisCount], uint16_t max_step_um) {
  int32_t d[3];
  for (uint8_t i = 0; i < 3; ++i) {
    LineAxis& a = split_.axis[i];
    a.to_um = target_um[i];
    a.at_um = planned_um_[i];
    d[i] = target_um[i] - planned_um_[i];
  }
  const uint32_t ax = core::abs_u32(d[0]);
  const uint32_t ay = core::abs_u32(d[1]);
  const uint32_t span = ax > ay ? ax : ay;
  split_.on_line = max_step_um != 0 && span > max_step_um;
  uint16_t step = max_step_um;
  if (map_ != 0 && map_->active() && target_um[2] <= 0 && planned_um_[2] <= 0 &&
      (step == 0 || step > kFollowStepUm))
    step = kFollowStepUm;
  uint32_t n = 1;
  if (step != 0 && span > step) {
    uint16_t rest = 0;
    n = core::div_u32_by_u16(span, step, &rest);
    if (rest != 0) ++n;
  }
  split_.pieces = n;
  split_.left = n;
  if (n == 1) return;
  // Pieces of a #U split stand for the line (see push()); n > 1: d is not zero.
  if (split_.on_line) unit_direction_q14(d, split_.dir_q14);
  for (uint8_t i = 0; i < 3; ++i) {
    // A 32/32 division: once per axis of a split segment, in the background (a 32/16 path
    // beside it for up to 65 535 pieces was 0.1 kB of flash on the AVR proxy).
    const uint32_t ad = core::abs_u32(d[i]);
    const uint32_t q = ad / n;
    const uint32_t r = ad % n;
    LineAxis& a = split_.axis[i];
    a.step_um = d[i] < 0 ? -(int32_t)q : (int32_t)q;
    a.unit = (int8_t)(d[i] < 0 ? -1 : 1);
    a.frac = r;
    a.acc = n >> 1;  // rounds each piece's end to the nearest micrometre
  }
}

bool Planner::push_segment(CoordinateRing* ring, const int32_t target_um[config::kAxisCount],
                           uint16_t feed_um_s, uint8_t flags, uint16_t tag,
                           const int16_t* line_dir_q14) {
  if (ring->free_space() == 0) return false;
  PlanEntry e;
  fill_segment(&e, target_um, line_dir_q14);
  e.feed_um_s = feed_um_s;
  e.flags = flags;
  e.tag = tag;
  // Until the next point is known the turn there may be anything: smallest capture.
  e.capture_um = settings_.cut_tolerance_um;
  const uint32_t feed_cap = (uint32_t)feed_um_s * settings_.max_override_percent / 100U;
  uint16_t cap = min16(e.cruise_max_um_s, feed_cap > kMaxSpeed ? kMaxSpeed : (uint16_t)feed_cap);
  int16_t turn_q14 = 0;  // this corner's sin(theta/2), signed as the turn in XY
  if (have_dir_) {
    cap = min16(cap, last_cruise_um_s_);
    int32_t omc_q14 = (int32_t)kOneQ14 - dot_q14(last_dir_q14_, e.dir_q14);
    if (omc_q14 > 0) {
      // sin(theta/2) = sqrt((1 - cos theta) / 2), Q14: one root for both limits.
      uint32_t sin_half_q14 = core::isqrt32((uint32_t)omc_q14 << 13);
      const uint8_t axes = involved_axes(last_dir_q14_, e.dir_q14);
      const int32_t cross =
          (int32_t)last_dir_q14_[0] * e.dir_q14[1] - (int32_t)last_dir_q14_[1] * e.dir_q14[0];
      turn_q14 = (int16_t)(cross < 0 ? -(int32_t)sin_half_q14 : (int32_t)sin_half_q14);
      if (e.length_um != 0 && last_length_um_ != 0) {
        cap = min16(cap, curve_speed(axes, sin_half_q14, last_length_um_, e.length_um));
        // A jog: a turn back against the last one within two capture radii. The ramp's lag
        // from the first has not died out, so their velocity steps add up: the corner is
        // priced with 2 sin(theta/2) the sum of both (at most a reversal).
        if ((turn_q14 ^ last_turn_q14_) < 0 && last_length_um_ < 2U * settings_.capture_radius_um) {
          sin_half_q14 += (uint32_t)(last_turn_q14_ < 0 ? -last_turn_q14_ : last_turn_q14_);
          if (sin_half_q14 > kOneQ14) sin_half_q14 = kOneQ14;
          omc_q14 = (int32_t)((sin_half_q14 * sin_half_q14) >> 13);  // 2 sin^2(theta/2)
        }
      }
      cap = min16(cap, corner_speed(axes, omc_q14, sin_half_q14));
    }
    // The corner is at the last point with length; zero-length markers after it sit on the
    // same point and get the same radius.
    const uint16_t capture = capture_for(last_dir_q14_, e.dir_q14);
    for (uint16_t k = 0;; ++k) {
      PlanEntry* prev = ring->newest(k);
      if (prev == 0) break;
      prev->capture_um = capture;
      if (prev->length_um != 0) break;
    }
  } else {
    cap = 0;  // the machine is at rest at the origin
  }
  e.junction_max_um_s = cap;
  e.entry_max_um_s = 0;
  ring->push(e);                                  // cannot fail: checked above, only this side adds
  memmove(last_um_, target_um, sizeof last_um_);  // push_standing: target_um is last_um_
  memcpy(last_dir_q14_, e.dir_q14, sizeof last_dir_q14_);
  last_cruise_um_s_ = e.cruise_max_um_s;
  if (e.length_um != 0) {
    last_length_um_ = e.length_um;
    last_turn_q14_ = turn_q14;
  }
  have_dir_ = true;
  replan(ring);
  return true;
}

// Backward pass from the newest entry (which must end at rest) toward the oldest. Limits
// only ever rise when a segment is appended, so the pass stops at the first unchanged one.
inline void Planner::replan(CoordinateRing* ring) {
  uint16_t exit = 0;
  for (uint16_t k = 0;; ++k) {
    PlanEntry* e = ring->newest(k);
    if (e == 0) break;
    uint16_t v = reach_speed_um_s(exit, e->accel_um_s_per_ms, e->length_um);
    if (v > e->junction_max_um_s) v = e->junction_max_um_s;
    if (k > 0 && v <= e->entry_max_um_s) break;
    e->entry_max_um_s = v;
    exit = v;
  }
}

}  // namespace app
