// Point generator engine: chord-adaptive parameter steps along a validated
// spline, tool-radius offset along the normal, corner arcs and miters, stop on overcut.
#include "firmware/core/curve_walker.h"

#include <string.h>  // memset

#include "firmware/core/divide.h"        // div_u32_u16
#include "firmware/core/fixed_point.h"   // mul_32x16_q15, mul_u16_u16, abs_u32, kUq16One
#include "firmware/core/isqrt.h"         // isqrt32
#include "firmware/core/wide_product.h"  // mul_wide, mul_q30

namespace core {

namespace {

// |(dx, dy)| in q6 (|dx|, |dy| < 2^31): scaled into 15 bits, isqrt, scaled back.
uint32_t length_q6(int32_t dx, int32_t dy) {
  uint32_t ax = abs_u32(dx);
  uint32_t ay = abs_u32(dy);
  uint8_t shift = 0;
  while ((ax | ay) >= (1UL << 23)) {  // whole bytes first (a variable shift is a bit loop)
    ax >>= 8;
    ay >>= 8;
    shift = (uint8_t)(shift + 8);
  }
  while ((ax | ay) >= 32768) {
    ax >>= 1;
    ay >>= 1;
    ++shift;
  }
  const uint16_t sx = (uint16_t)ax;
  const uint16_t sy = (uint16_t)ay;
  return (uint32_t)isqrt32(mul_u16_u16(sx, sx) + mul_u16_u16(sy, sy)) << shift;
}

// Sign of |(dx, dy)| - 1 um (64 q6), exactly (no root for most vectors): > 0 longer, < 0
// shorter.
int8_t versus_1um(int32_t dx, int32_t dy) {
  const uint32_t ax = abs_u32(dx);
  const uint32_t ay = abs_u32(dy);
  if (ax > 64 || ay > 64) return 1;
  const uint32_t s =
      mul_u16_u16((uint16_t)ax, (uint16_t)ax) + mul_u16_u16((uint16_t)ay, (uint16_t)ay);
  return s > 64 * 64 ? 1 : (s < 64 * 64 ? -1 : 0);
}

}  // namespace

// The chord a -> b of one trial step, prepared once for the distances of all its samples:
// b - a shifted left (exactly: the direction is b - a's own) so that its larger component
// lies in [2^29, 2^30), and 2^29 / (|n| / 2^16), so that a distance is two products.
struct Chord {
  const PointQ6* a;  // the walker's last point: not copied (a smaller frame)
  int32_t bx;
  int32_t by;
  int32_t nx;
  int32_t ny;
  int16_t nx16;  // n / 2^16 (14 significant bits): enough for the projection
  int16_t ny16;
  int32_t along_end;     // (b - a) . n / 2^32: where the projection leaves the segment
  uint16_t inv_len_q15;  // 2^29 / |n16|: |n| / 2^30 is in [1/2, 1.42)
  bool short_chord;      // |b - a| < 1 um: distances are to a
};

namespace {

// floor(v * s / 2^16) for |v| < 2^30 and a signed 16-bit s: two 16x16 products.
int32_t mul_32x16_hi(int32_t v, int16_t s) {
  const int32_t lo = mul_s16_u16(s, low_half(v));  // |.| < 2^31
  return (int32_t)high_half(v) * s + (int32_t)high_half(lo);
}

// (qx, qy) . n / 2^32 from the 14-bit n (|.| < 2^30 for |q| < 2^29).
int32_t along_q32(const Chord& c, int32_t qx, int32_t qy) {
  return mul_32x16_hi(qx, c.nx16) + mul_32x16_hi(qy, c.ny16);
}

void make_chord(const PointQ6& a, const PointQ6& b, Chord* out) {
  Chord& c = *out;
  c.a = &a;
  c.bx = b.x_q6 - a.x_q6;  // |.| < 2^28: coordinates and offsets stay below 2^27
  c.by = b.y_q6 - a.y_q6;
  c.short_chord = versus_1um(c.bx, c.by) < 0;
  if (c.short_chord) return;                   // nothing else is read of a short chord
  uint32_t m = abs_u32(c.bx) | abs_u32(c.by);  // same leading bit as the larger, >= 45
  uint32_t nx = (uint32_t)c.bx;
  uint32_t ny = (uint32_t)c.by;
  while (m < (1UL << 21)) {  // whole bytes first
    m <<= 8;
    nx <<= 8;
    ny <<= 8;
  }
  while (m < (1UL << 29)) {
    m <<= 1;
    nx <<= 1;
    ny <<= 1;
  }
  c.nx = (int32_t)nx;
  c.ny = (int32_t)ny;
  c.nx16 = high_half(c.nx);
  c.ny16 = high_half(c.ny);
  c.along_end = along_q32(c, c.bx, c.by);
  const uint16_t ax = (uint16_t)abs_u32(c.nx16);
  const uint16_t ay = (uint16_t)abs_u32(c.ny16);
  const uint16_t len = isqrt32(mul_u16_u16(ax, ax) + mul_u16_u16(ay, ay));  // [2^13, 2^14.5)
  c.inv_len_q15 = div_u32_u16((1UL << 29) - 1, len, 0);                     // < 2^16
}

// Distance (q6) from q to the chord: to the line when q projects inside the segment, else
// to the nearer end (a hairpin tip can poke out past an end). Relative error ~2^-13.
uint32_t chord_distance_q6(const Chord& c, const PointQ6& q) {
  const int32_t qx = q.x_q6 - c.a->x_q6;
  const int32_t qy = q.y_q6 - c.a->y_q6;
  if (c.short_chord) return length_q6(qx, qy);
  // The projection with 14-bit n: it only picks the formula, and at its two boundaries the
  // line distance and the end distance agree.
  const int32_t along = along_q32(c, qx, qy);
  if (along <= 0) return length_q6(qx, qy);
  if (along >= c.along_end) return length_q6(qx - c.bx, qy - c.by);
  // |q x n| / 2^30 (< 2^29), times 2^30 / |n| = inv_len_q15 / 2^15.
  const uint32_t cross = abs_u32(mul_q30(qx, c.ny) - mul_q30(qy, c.nx));
  return (uint32_t)mul_32x16_uq16((int32_t)cross, c.inv_len_q15) << 1;
}

// The chord error of a polynomial step without offset, in closed form. With
// P(t0 + h s) = a + a1 s + a2 s^2 + a3 s^3 and b - a = a1 + a2 + a3, the curve leaves the
// chord by D(s) = s (s - 1) (a2 + (s + 1) a3); its distances from the chord line at
// s = 1/4, 1/2, 3/4 (the three samples of the evaluated path) follow from the two cross
// products a2 x n and a3 x n: no point is evaluated. False (the caller samples the path)
// when a sample could project beyond the chord's ends, where the distance is to the end:
// |D(s)| <= (|a2| + 2 |a3|) / 4 < |b - a| / 4 keeps them inside.
bool polynomial_step_error(const SpanEvaluator& eval, const Chord& c, uint32_t t0_q16,
                           uint32_t step_q16, uint32_t* worst) {
  if (c.short_chord) return false;
  PointQ6 a2;
  PointQ6 a3;
  if (!eval.step_bend_q6(t0_q16, step_q16, &a2, &a3)) return false;
  // Halved 1-norms (>= the halved lengths; < 2^31 each) against the chord's larger
  // component (<= its length).
  const uint32_t bend_half =
      ((abs_u32(a2.x_q6) + abs_u32(a2.y_q6)) >> 1) + abs_u32(a3.x_q6) + abs_u32(a3.y_q6);
  const uint32_t ax = abs_u32(c.bx);
  const uint32_t ay = abs_u32(c.by);
  if (bend_half >= ((ax > ay ? ax : ay) >> 1)) return false;
  // a x n / 2^30 (|a2| + 2 |a3| < 2^28 and |n| < 2^30.5: 4 x2 + 7 x3 < 2^30.5).
  const int32_t x2 = mul_q30(a2.x_q6, c.ny) - mul_q30(a2.y_q6, c.nx);
  const int32_t x3 = mul_q30(a3.x_q6, c.ny) - mul_q30(a3.y_q6, c.nx);
  // |D| x n at s = 1/4, 3/4: 3 |4 x2 + 5 x3| / 64, 3 |4 x2 + 7 x3| / 64; at 1/2 |2 x2 + 3 x3| / 8.
  const uint32_t q1 = abs_u32(4 * x2 + 5 * x3) >> 2;
  const uint32_t q3 = abs_u32(4 * x2 + 7 * x3) >> 2;
  uint32_t m = ((q1 > q3 ? q1 : q3) * 3) >> 4;
  const uint32_t mid = abs_u32(2 * x2 + 3 * x3) >> 3;
  if (mid > m) m = mid;
  *worst = (uint32_t)mul_32x16_uq16((int32_t)m, c.inv_len_q15) << 1;  // times 2^30 / |n|
  return true;
}

bool is_zero(const Direction& d) {
  return d.dx == 0 && d.dy == 0;
}

// Largest q8 factor sqrt(target / err) clamped to [lo_q8, hi_q8] (16 <= lo, hi <= 512): the
// step ratio that would bring a chord error err (which scales with h^2) to target. The
// ratio is one 32/16 division on err normalised to 16 bits (q14 when >= 1, else q16).
uint16_t step_factor_q8(uint32_t target, uint32_t err, uint16_t lo_q8, uint16_t hi_q8) {
  if (err <= (target >> 2)) return hi_q8;  // ratio >= 4: f >= 512
  if ((err >> 8) > target) return lo_q8;   // ratio < 1/256: f < 16
  uint32_t e = err;
  int8_t k = 0;  // err ~ e * 2^k with e in [2^15, 2^16)
  while (e >= (1UL << 16)) {
    e >>= 1;
    ++k;
  }
  while (e < (1UL << 15)) {
    e <<= 1;
    --k;
  }
  const uint8_t frac = target >= err ? 14 : 16;  // the quotient stays below 2^16
  const int8_t s = (int8_t)(frac - k);
  const uint32_t n = s >= 0 ? target << s : target >> -s;  // < (e + 1) 2^16 (ratio bound)
  const uint16_t q = (n >> 16) >= e ? 0xFFFFU : div_u32_u16(n, (uint16_t)e, 0);
  const uint32_t ratio_q16 = frac == 14 ? (uint32_t)q << 2 : q;
  uint16_t f = isqrt32(ratio_q16);  // sqrt(ratio) in q8
  if (f < lo_q8) f = lo_q8;
  if (f > hi_q8) f = hi_q8;
  return f;
}

// step * f / 256 for step <= 2^16 and f <= 512, without a 32x32 product.
uint32_t scale_step_q8(uint32_t step, uint16_t f_q8) {
  if (step >= kUq16One) return (uint32_t)f_q8 << 8;
  return mul_u16_u16((uint16_t)step, f_q8) >> 8;
}

// trunc(r 64 s / denom), the miter's offset (q6), for |r| <= 10^5, |s| <= 2^16 and denom in
// [4390, 65536]: the product held wide (< 2^39) and divided in two 32/16 steps.
int32_t miter_q6(int32_t r, int32_t s, uint32_t denom) {
  const Wide mag = mul_wide((int32_t)abs_u32(r * 64), (int32_t)abs_u32(s));
  uint32_t q;
  if (denom >= 65536UL) {
    q = wide_shift_right_low(mag, 16);
  } else {
    // Digits mag.hi (< 2^7 < denom), mag.lo's high and low halves.
    uint16_t rem = 0;
    const uint16_t d = (uint16_t)denom;
    const uint16_t q_hi = div_u32_u16((mag.hi << 16) | (mag.lo >> 16), d, &rem);
    const uint16_t q_lo = div_u32_u16(((uint32_t)rem << 16) | (mag.lo & 0xFFFFU), d, 0);
    q = ((uint32_t)q_hi << 16) | q_lo;
  }
  return ((r < 0) != (s < 0)) ? -(int32_t)q : (int32_t)q;
}

// |R| sin(turn) * 4 <= tol, i.e. r_abs |cross| <= tol 2^28 (exact, the product wide).
bool smooth_turn(int32_t r_abs, int32_t cross_q30, uint16_t tol_um) {
  Wide tol_q28;
  tol_q28.hi = (uint32_t)tol_um >> 4;
  tol_q28.lo = (uint32_t)tol_um << 28;
  const Wide gap_q30 = mul_wide(r_abs, (int32_t)abs_u32(cross_q30));  // ~ |R| sin
  return !wide_negative(wide_sub(tol_q28, gap_q30));
}

// Sign of ax * bx + ay * by < 0, exactly (32x32 products held wide).
bool dot_negative(int32_t ax, int32_t ay, int32_t bx, int32_t by) {
  return wide_negative(wide_add(mul_wide(ax, bx), mul_wide(ay, by)));
}

}  // namespace

StepSettings default_step_settings() {
  StepSettings s;
  s.mode = StepMode::kAdaptive;
  s.chord_tolerance_um = kDefaultChordToleranceUm;
  s.tool_offset_um = 0;
  return s;
}

// Every member starts at zero (idle, kOk, no spline, zero points and normals: all of them
// plain data), then the defaults that are not zero. One memset instead of a store per
// member: the stores were 354 B of flash on the AVR proxy.
CurveWalker::CurveWalker() {
  memset(static_cast<void*>(this), 0, sizeof *this);
  settings_ = default_step_settings();
  last_dir_.dx = 1;
}

// Checks spline and settings; the first point comes from the next next() call.
GeometryError CurveWalker::begin(const Spline* spline, const StepSettings& settings) {
  spline_ = spline;
  settings_ = settings;
  phase_ = kDone;
  pending_ = false;
  arc_.stop();
  error_ = GeometryError::kOk;
  if (spline == 0) return error_ = GeometryError::kKnotRangeEmpty;
  error_ = validate_spline(*spline);
  if (error_ != GeometryError::kOk) return error_;
  if (settings.mode != StepMode::kAdaptive || settings.chord_tolerance_um == 0 ||
      settings.chord_tolerance_um > 10000) {
    return error_ = GeometryError::kToleranceInvalid;
  }
  if (settings.tool_offset_um > kMaxToolOffsetUm || settings.tool_offset_um < -kMaxToolOffsetUm) {
    return error_ = GeometryError::kOffsetTooLarge;
  }
  // Adaptive thresholds 0.9 and 0.7 tol in q6 (< 2^20), once here, not per step.
  const uint32_t tol_q6 = (uint32_t)settings.chord_tolerance_um * 64;
  accept_q6_ = tol_q6 * 9 / 10;
  target_q6_ = tol_q6 * 7 / 10;
  phase_ = kStart;
  return error_;
}

// One span setup or one point per call (see the header).
bool CurveWalker::next(PointUm* out) {
  if (phase_ == kDone || phase_ == kIdle) return false;
  if (pending_) {
    pending_ = false;
    return emit_plain(pending_point_, out);
  }
  if (arc_.active()) return arc_point(out);
  if (phase_ == kStart) {
    if (!enter_span(first_span(*spline_))) return false;
    phase_ = kInSpan;
    Direction d;
    const PointQ6 p = path_point(0, &d);
    last_base_ = eval_.evaluate_q6(0);
    return emit_plain(p, out);
  }
  return step_in_span(out);
}

// Sets span up and steps from its start; false (stopped) when the setup refuses it.
bool CurveWalker::enter_span(uint16_t span) {
  const GeometryError e = eval_.setup(*spline_, span);
  if (e != GeometryError::kOk) return fail(e);
  span_ = span;
  t_q16_ = 0;
  h_q16_ = kUq16One;  // a new span may be much flatter than the last: try it whole first
  return true;
}

// Stops stepping with a coded reason.
bool CurveWalker::fail(GeometryError e) {
  error_ = e;
  phase_ = kDone;
  arc_.stop();
  pending_ = false;
  return false;
}

// Emits the next point inside the span, or handles the span's end.
// Always inline: next() is its one caller (-64 B on the AVR proxy).
inline __attribute__((always_inline)) bool CurveWalker::step_in_span(PointUm* out) {
  const uint32_t t_next = adaptive_next();
  if (t_next >= kUq16One) return joint(out);
  t_q16_ = t_next;
  return emit_checked(step_base_, step_point_, out);  // the accepted trial's end
}

// Chord-adaptive step: the longest step (within the span) whose path points at 1/4, 1/2
// and 3/4 lie within 0.9 * tolerance of the chord line. For a polynomial span the
// distance to the chord is a cubic in the step fraction that vanishes at both ends, so
// three samples bound its maximum within 6 %: the real chord error stays <= 0.95 tol.
// There (no offset) the samples' distances come in closed form from the step's Taylor
// coefficients (polynomial_step_error): one evaluation per trial instead of four.
// Rational spans and offset paths are not polynomial: they get 7 samples (eighths), which
// the tests show to be enough on random curves; it is not a proof.
// Bounded: a rejected step shrinks to at most half and a step of 1/65536 is accepted.
uint32_t CurveWalker::adaptive_next() {
  uint32_t h = h_q16_ < 1 ? 1 : h_q16_;
  const uint8_t parts_log2 = (eval_.rational() || settings_.tool_offset_um != 0) ? 3 : 2;
  for (uint8_t tries = 0; tries < 24; ++tries) {
    uint32_t t1 = t_q16_ + h;
    if (t1 > kUq16One) t1 = kUq16One;
    const uint32_t step = t1 - t_q16_;
    // The trial's end straight into the members that keep the accepted one (a rejected
    // trial's are overwritten by the next): no copies in this frame.
    Direction d;
    step_point_ = path_point(t1, &d);
    step_base_ = path_base_;
    const uint32_t worst = trial_error(step, parts_log2);
    if (worst <= accept_q6_ || step <= 1) {
      // Next step: grow toward the target error (chord error ~ h^2), at most x2.
      const uint32_t grown = scale_step_q8(step, step_factor_q8(target_q6_, worst, 256, 512));
      h_q16_ = grown < 1 ? 1 : (grown > kUq16One ? kUq16One : grown);
      if (t1 >= kUq16One && h_q16_ < h) h_q16_ = h;  // a short last step says nothing
      return t1;
    }
    // Shrink 1/16 .. 1/2.
    h = scale_step_q8(step, step_factor_q8(target_q6_, worst, 16, 128));
    if (h < 1) h = 1;
  }
  return t_q16_ + 1;  // not reached: 24 halvings take any step down to 1
}

// The chord error of the trial step from the last point to step_point_: on a polynomial
// span without offset (parts_log2 2) the samples' distances in closed form, else sampled.
// Out of line: the chord stays out of adaptive_next()'s frame, which then fits the AVR's
// 63-byte displacement (a larger frame costs two instructions per access beyond it).
__attribute__((noinline)) uint32_t CurveWalker::trial_error(uint32_t step, uint8_t parts_log2) {
  Chord chord;
  make_chord(last_out_, step_point_, &chord);
  uint32_t worst = 0;
  if (parts_log2 != 2 || !polynomial_step_error(eval_, chord, t_q16_, step, &worst)) {
    worst = sampled_error(chord, step, parts_log2);
  }
  return worst;
}

// The largest distance from the chord of the path points at q / 2^parts_log2 of the step
// (q = 1 .. 2^parts_log2 - 1). Out of line: the samples' temporaries stay out of
// adaptive_next()'s frame.
__attribute__((noinline)) uint32_t CurveWalker::sampled_error(const Chord& chord, uint32_t step,
                                                              uint8_t parts_log2) {
  const uint8_t parts = (uint8_t)(1U << parts_log2);
  uint32_t worst = 0;
  uint32_t step_q = 0;  // step * q, so that t = t_q16_ + step * q / parts is a shift
  for (uint8_t q = 1; q < parts; ++q) {
    step_q += step;
    Direction d;
    const PointQ6 mid = path_point(t_q16_ + (step_q >> parts_log2), &d);
    const uint32_t e = chord_distance_q6(chord, mid);
    if (e > worst) worst = e;
  }
  return worst;
}

// The end of the current span: the last point of the curve, or the joint to the next span
// (plain, discontinuous, smooth, or a corner).
bool CurveWalker::joint(PointUm* out) {
  Direction in_dir = eval_.end_direction();
  if (is_zero(in_dir)) in_dir = last_dir_;
  const PointQ6 end = eval_.evaluate_q6(kUq16One);
  const uint16_t ns = next_span(*spline_, span_);
  if (ns >= span_end(*spline_)) {
    phase_ = kDone;
    const int32_t r = settings_.tool_offset_um;
    const PointQ6 p = r == 0 ? end : offset_point(end, left_unit_normal(in_dir));
    t_q16_ = kUq16One;
    return emit_checked(end, p, out);
  }
  if (!enter_span(ns)) return false;
  const PointQ6 start = eval_.start_q6();
  Direction out_dir = usable_direction(0);
  if (is_zero(out_dir)) out_dir = in_dir;
  last_dir_ = out_dir;
  const bool jump = versus_1um(end.x_q6 - start.x_q6, end.y_q6 - start.y_q6) > 0;
  if (settings_.tool_offset_um == 0) {
    if (jump) {
      pending_ = true;
      pending_point_ = start;
    }
    last_base_ = start;
    return emit_plain(end, out);
  }
  if (jump) {
    // Discontinuous curve (knot multiplicity degree + 1): end, then start, each offset.
    pending_ = true;
    pending_point_ = offset_point(start, left_unit_normal(out_dir));
    const PointQ6 p = offset_point(end, left_unit_normal(in_dir));
    const bool ok = emit_checked(end, p, out);
    last_base_ = start;
    return ok;
  }
  return corner(end, in_dir, out_dir, out);
}

// Offset at a joint. Smooth (offset points within tol/4): one point. Convex (turning away
// from the offset side): the first offset end, then an arc of radius |R| about the
// corner to the second. Concave: the miter point, or kOffsetTooLarge past ~150 degrees.
bool CurveWalker::corner(const PointQ6& at, const Direction& in_dir, const Direction& out_dir,
                         PointUm* out) {
  const int32_t r = settings_.tool_offset_um;
  const UnitQ15 n1 = left_unit_normal(in_dir);
  const UnitQ15 n2 = left_unit_normal(out_dir);
  // Unit normals (|n| <= 2^15 (1 + 2^-14)): cross and dot < 2^31 in magnitude. 32-bit and
  // 16x16 arithmetic only here (64-bit code is large on 8- and 16-bit cores).
  const int32_t cross_q30 = n1.x_q15 * n2.y_q15 - n1.y_q15 * n2.x_q15;
  const int32_t dot_q30 = n1.x_q15 * n2.x_q15 + n1.y_q15 * n2.y_q15;
  const int32_t r_abs = (int32_t)abs_u32(r);  // <= kMaxToolOffsetUm
  if (dot_q30 > 0 && smooth_turn(r_abs, cross_q30, settings_.chord_tolerance_um)) {
    return emit_checked(at, offset_point(at, n2), out);
  }
  // Turning left (cross > 0) puts a left offset (R > 0) on the inside: concave. An exact
  // reversal (cross 0) is convex on both sides: the tool goes round the end.
  const bool concave = cross_q30 != 0 && (cross_q30 > 0) == (r > 0);
  if (concave) {
    const int32_t denom_q15 = 32768 + (dot_q30 >> 15);                  // 1 + cos(turn)
    if (denom_q15 < 4390) return fail(GeometryError::kOffsetTooLarge);  // turn > ~150 deg
    // Miter: at + R (n1 + n2) / (1 + n1.n2).
    PointQ6 m;
    m.x_q6 = at.x_q6 + miter_q6(r, n1.x_q15 + n2.x_q15, (uint32_t)denom_q15);
    m.y_q6 = at.y_q6 + miter_q6(r, n1.y_q15 + n2.y_q15, (uint32_t)denom_q15);
    return emit_checked(at, m, out);
  }
  // Convex: an arc of radius |R| about the corner from n1 to n2.
  arc_.begin(at, n1, n2, dot_q30<0, r> 0, (uint32_t)r_abs, settings_.chord_tolerance_um);
  return emit_checked(at, offset_point(at, n1), out);
}

// One point of the corner arc: offset along the arc's next normal.
bool CurveWalker::arc_point(PointUm* out) {
  const PointQ6 p = offset_point(arc_.center(), arc_.next_normal());
  last_base_ = arc_.center();
  return emit_plain(p, out);
}

// Path point at t: the curve point, moved by the tool offset along the left normal.
PointQ6 CurveWalker::path_point(uint32_t t_q16, Direction* dir) {
  const PointQ6 base = eval_.evaluate_q6(t_q16);
  path_base_ = base;
  if (settings_.tool_offset_um == 0) return base;
  *dir = usable_direction(t_q16);
  if (is_zero(*dir)) *dir = last_dir_;
  return offset_point(base, left_unit_normal(*dir));
}

// Derivative direction at t; at a zero derivative (a cusp or repeated control points)
// looks slightly further along, then falls back to the last direction.
Direction CurveWalker::usable_direction(uint32_t t_q16) {
  if (t_q16 >= kUq16One) return eval_.end_direction();
  Direction d = eval_.direction((uq16_t)t_q16);
  for (uint32_t probe = 16; is_zero(d) && probe <= 4096; probe *= 16) {
    const uint32_t t = t_q16 + probe < kUq16One ? t_q16 + probe : kUq16One - 1;
    d = eval_.direction((uq16_t)t);
  }
  if (is_zero(d)) d = last_dir_;
  return d;
}

// base + R * normal, in q6: R * 64 < 2^23 times |normal| <= 2^15 as 16x16 products on the
// magnitudes (truncated toward zero, the sign applied after).
PointQ6 CurveWalker::offset_point(const PointQ6& base, const UnitQ15& n) const {
  const int32_t r_q6 = settings_.tool_offset_um * 64;
  const uint32_t ar = abs_u32(r_q6);
  const uint16_t ar_hi = (uint16_t)(ar >> 16);  // < 2^7
  const uint16_t ar_lo = (uint16_t)ar;
  int32_t off[2];
  const int32_t comp[2] = {n.x_q15, n.y_q15};
  for (uint8_t i = 0; i < 2; ++i) {
    const uint16_t an = (uint16_t)abs_u32(comp[i]);  // <= 2^15
    // (hi 2^16 + lo) an / 2^15 = 2 hi an + lo an / 2^15; hi an < 2^22, lo an < 2^31.
    const uint32_t mag = (mul_u16_u16(ar_hi, an) << 1) + (mul_u16_u16(ar_lo, an) >> 15);
    off[i] = ((r_q6 < 0) != (comp[i] < 0)) ? -(int32_t)mag : (int32_t)mag;
  }
  PointQ6 p;
  p.x_q6 = base.x_q6 + off[0];
  p.y_q6 = base.y_q6 + off[1];
  return p;
}

// Emits p after checking that the offset path does not run backward against the curve
// (which means |R| exceeds the radius of curvature on the offset side).
bool CurveWalker::emit_checked(const PointQ6& base, const PointQ6& p, PointUm* out) {
  if (settings_.tool_offset_um != 0) {
    // Differences < 2^28 (coordinates and offsets < 2^27 q6): 32-bit, products held wide.
    const int32_t bx = base.x_q6 - last_base_.x_q6;
    const int32_t by = base.y_q6 - last_base_.y_q6;
    const int32_t ox = p.x_q6 - last_out_.x_q6;
    const int32_t oy = p.y_q6 - last_out_.y_q6;
    if (versus_1um(bx, by) > 0 && dot_negative(bx, by, ox, oy)) {
      return fail(GeometryError::kOffsetTooLarge);
    }
  }
  last_base_ = base;
  return emit_plain(p, out);
}

// Emits p (rounded to um) and remembers it.
bool CurveWalker::emit_plain(const PointQ6& p, PointUm* out) {
  last_out_ = p;
  *out = round_point(p);
  return true;
}

}  // namespace core
