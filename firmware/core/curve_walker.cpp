// Point generator engine: uniform or chord-adaptive parameter steps along a validated
// spline, tool-radius offset along the normal, corner arcs and miters, stop on overcut.
#include "firmware/core/curve_walker.h"

#include "firmware/core/divide.h"       // div_u32_u16
#include "firmware/core/fixed_point.h"  // mul_32x16_q15, mul_u16_u16, abs_u32, kUq16One
#include "firmware/core/isqrt.h"        // isqrt32

namespace core {

namespace {

// Squared length of a q6 difference, in q12 um^2 (64-bit: differences reach 2^27).
int64_t dist2_q12(const PointQ6& a, const PointQ6& b) {
  const int64_t dx = (int64_t)a.x_q6 - b.x_q6;
  const int64_t dy = (int64_t)a.y_q6 - b.y_q6;
  return dx * dx + dy * dy;
}

// |(dx, dy)| for 64-bit components: scaled into 15 bits, isqrt, scaled back.
int64_t length_q6(int64_t dx, int64_t dy) {
  if (dx < 0) dx = -dx;
  if (dy < 0) dy = -dy;
  uint8_t shift = 0;
  while ((dx >> shift) >= 32768 || (dy >> shift) >= 32768) ++shift;
  const uint32_t sx = (uint32_t)(dx >> shift);
  const uint32_t sy = (uint32_t)(dy >> shift);
  return (int64_t)isqrt32(sx * sx + sy * sy) << shift;
}

// Distance (q6) from q to the segment ab: to the line when q projects inside the
// segment, else to the nearer end (a hairpin tip can poke out past an end).
int64_t chord_distance_q6(const PointQ6& a, const PointQ6& b, const PointQ6& q) {
  const int64_t bx = (int64_t)b.x_q6 - a.x_q6;
  const int64_t by = (int64_t)b.y_q6 - a.y_q6;
  const int64_t qx = (int64_t)q.x_q6 - a.x_q6;
  const int64_t qy = (int64_t)q.y_q6 - a.y_q6;
  const int64_t len = length_q6(bx, by);
  const int64_t along = bx * qx + by * qy;  // |b - a| * projection, < 2^55
  if (len < 64 || along <= 0) return length_q6(qx, qy);
  if (along >= bx * bx + by * by) return length_q6(qx - bx, qy - by);
  const int64_t cross = bx * qy - by * qx;  // < 2^55
  return (cross < 0 ? -cross : cross) / len;
}

bool is_zero(const Direction& d) {
  return d.dx == 0 && d.dy == 0;
}

// Largest q8 factor sqrt(target / err) clamped to [lo_q8, hi_q8]: the step ratio that
// would bring a chord error err (which scales with h^2) to target.
uint32_t step_factor_q8(int64_t target, int64_t err, uint32_t lo_q8, uint32_t hi_q8) {
  if (err <= 0) return hi_q8;
  int64_t ratio_q16 = target * 65536 / err;
  if (ratio_q16 > 0xFFFFFFFFLL) ratio_q16 = 0xFFFFFFFFLL;
  uint32_t f = isqrt32((uint32_t)ratio_q16);  // sqrt(ratio) in q8
  if (f < lo_q8) f = lo_q8;
  if (f > hi_q8) f = hi_q8;
  return f;
}

}  // namespace

StepSettings default_step_settings() {
  StepSettings s;
  s.mode = StepMode::kAdaptive;
  s.steps_per_span = 16;
  s.chord_tolerance_um = kDefaultChordToleranceUm;
  s.tool_offset_um = 0;
  return s;
}

CurveWalker::CurveWalker()
    : spline_(0),
      phase_(kIdle),
      error_(GeometryError::kOk),
      span_(0),
      step_index_(0),
      t_q16_(0),
      h_q16_(0),
      tol_um_(kDefaultChordToleranceUm),
      pending_(false),
      arc_steps_(0),
      arc_index_(0),
      arc_halves_left_(0) {
  settings_ = default_step_settings();
  last_dir_.dx = 1;
  last_dir_.dy = 0;
  last_out_.x_q6 = last_out_.y_q6 = 0;
  last_base_ = pending_point_ = arc_center_ = last_out_;
  arc_a_.x_q15 = arc_a_.y_q15 = 0;
  arc_b_ = arc_c_ = arc_a_;
}

// Checks spline and settings; the first point comes from the next next() call.
GeometryError CurveWalker::begin(const Spline* spline, const StepSettings& settings) {
  spline_ = spline;
  settings_ = settings;
  phase_ = kDone;
  pending_ = false;
  arc_halves_left_ = 0;
  error_ = GeometryError::kOk;
  if (spline == 0) return error_ = GeometryError::kKnotRangeEmpty;
  error_ = validate_spline(*spline);
  if (error_ != GeometryError::kOk) return error_;
  if (settings.mode == StepMode::kUniform && settings.steps_per_span == 0) {
    return error_ = GeometryError::kToleranceInvalid;
  }
  if (settings.mode != StepMode::kUniform && settings.mode != StepMode::kAdaptive) {
    return error_ = GeometryError::kToleranceInvalid;
  }
  if (settings.mode == StepMode::kAdaptive &&
      (settings.chord_tolerance_um == 0 || settings.chord_tolerance_um > 10000)) {
    return error_ = GeometryError::kToleranceInvalid;
  }
  if (settings.tool_offset_um > kMaxToolOffsetUm || settings.tool_offset_um < -kMaxToolOffsetUm) {
    return error_ = GeometryError::kOffsetTooLarge;
  }
  tol_um_ = settings.chord_tolerance_um;
  if (tol_um_ == 0 || tol_um_ > 10000) tol_um_ = kDefaultChordToleranceUm;
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
  if (arc_halves_left_ > 0) return arc_point(out);
  if (phase_ == kStart) {
    span_ = first_span(*spline_);
    const GeometryError e = eval_.setup(*spline_, span_);
    if (e != GeometryError::kOk) return fail(e);
    t_q16_ = 0;
    step_index_ = 0;
    h_q16_ = kUq16One;
    phase_ = kInSpan;
    Direction d;
    const PointQ6 p = path_point(0, &d);
    last_base_ = eval_.evaluate_q6(0);
    return emit_plain(p, out);
  }
  return step_in_span(out);
}

// Stops stepping with a coded reason.
bool CurveWalker::fail(GeometryError e) {
  error_ = e;
  phase_ = kDone;
  arc_halves_left_ = 0;
  pending_ = false;
  return false;
}

// Next parameter of the uniform mode: k * 65536 / steps_per_span.
uint32_t CurveWalker::uniform_next() const {
  return (uint32_t)(((uint32_t)step_index_ + 1) * kUq16One / settings_.steps_per_span);
}

// Emits the next point inside the span, or handles the span's end.
bool CurveWalker::step_in_span(PointUm* out) {
  const uint32_t t_next = settings_.mode == StepMode::kUniform ? uniform_next() : adaptive_next();
  if (t_next >= kUq16One) return joint(out);
  t_q16_ = t_next;
  ++step_index_;
  Direction d;
  const PointQ6 p = path_point(t_next, &d);
  return emit_checked(eval_.evaluate_q6(t_next), p, out);
}

// Chord-adaptive step: the longest step (within the span) whose path points at 1/4, 1/2
// and 3/4 lie within 0.9 * tolerance of the chord line. For a polynomial span the
// distance to the chord is a cubic in the step fraction that vanishes at both ends, so
// three samples bound its maximum within 6 %: the real chord error stays <= 0.95 tol.
// Rational spans and offset paths are not polynomial: they get 7 samples (eighths), which
// the tests show to be enough on random curves; it is not a proof.
// Bounded: a rejected step shrinks to at most half and a step of 1/65536 is accepted.
uint32_t CurveWalker::adaptive_next() {
  const int64_t accept_q6 = (int64_t)tol_um_ * 64 * 9 / 10;
  const int64_t target_q6 = (int64_t)tol_um_ * 64 * 7 / 10;
  uint32_t h = h_q16_ < 1 ? 1 : h_q16_;
  for (uint8_t tries = 0; tries < 24; ++tries) {
    uint32_t t1 = t_q16_ + h;
    if (t1 > kUq16One) t1 = kUq16One;
    const uint32_t step = t1 - t_q16_;
    Direction d;
    const PointQ6 b = path_point(t1, &d);
    int64_t worst = 0;
    const uint32_t parts = (eval_.rational() || settings_.tool_offset_um != 0) ? 8 : 4;
    for (uint32_t q = 1; q < parts; ++q) {
      const PointQ6 mid = path_point(t_q16_ + step * q / parts, &d);
      const int64_t e = chord_distance_q6(last_out_, b, mid);
      if (e > worst) worst = e;
    }
    if (worst <= accept_q6 || step <= 1) {
      // Next step: grow toward the target error (chord error ~ h^2), at most x2.
      const uint32_t f = step_factor_q8(target_q6, worst, 256, 512);
      uint32_t grown = (uint32_t)((uint64_t)step * f / 256);
      h_q16_ = grown < 1 ? 1 : (grown > kUq16One ? kUq16One : grown);
      if (t1 >= kUq16One && h_q16_ < h) h_q16_ = h;  // a short last step says nothing
      return t1;
    }
    const uint32_t f = step_factor_q8(target_q6, worst, 16, 128);  // shrink 1/16 .. 1/2
    h = (uint32_t)((uint64_t)step * f / 256);
    if (h < 1) h = 1;
  }
  return t_q16_ + 1;  // not reached: 24 halvings take any step down to 1
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
    const PointQ6 p = r == 0 ? end : offset_point(end, left_normal(in_dir));
    t_q16_ = kUq16One;
    return emit_checked(end, p, out);
  }
  const GeometryError e = eval_.setup(*spline_, ns);
  if (e != GeometryError::kOk) return fail(e);
  span_ = ns;
  t_q16_ = 0;
  step_index_ = 0;
  h_q16_ = kUq16One;  // a new span may be much flatter: try it whole first
  const PointQ6 start = eval_.start_q6();
  Direction out_dir = usable_direction(0);
  if (is_zero(out_dir)) out_dir = in_dir;
  last_dir_ = out_dir;
  const bool jump = dist2_q12(end, start) > 64 * 64;  // more than 1 um apart
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
    pending_point_ = offset_point(start, left_normal(out_dir));
    const PointQ6 p = offset_point(end, left_normal(in_dir));
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
  const Unit n1 = left_normal(in_dir);
  const Unit n2 = left_normal(out_dir);
  const int64_t cross_q30 = (int64_t)n1.x_q15 * n2.y_q15 - (int64_t)n1.y_q15 * n2.x_q15;
  const int64_t dot_q30 = (int64_t)n1.x_q15 * n2.x_q15 + (int64_t)n1.y_q15 * n2.y_q15;
  const int64_t r_abs = r < 0 ? -(int64_t)r : r;
  const int64_t gap_q30 = r_abs * (cross_q30 < 0 ? -cross_q30 : cross_q30);  // ~ |R| sin
  if (dot_q30 > 0 && gap_q30 * 4 <= (int64_t)tol_um_ << 30) {
    return emit_checked(at, offset_point(at, n2), out);
  }
  // Turning left (cross > 0) puts a left offset (R > 0) on the inside: concave. An exact
  // reversal (cross 0) is convex on both sides: the tool goes round the end.
  const bool concave = cross_q30 != 0 && (cross_q30 > 0) == (r > 0);
  if (concave) {
    const int64_t denom_q15 = 32768 + (dot_q30 >> 15);                  // 1 + cos(turn)
    if (denom_q15 < 4390) return fail(GeometryError::kOffsetTooLarge);  // turn > ~150 deg
    // Miter: at + R (n1 + n2) / (1 + n1.n2).
    PointQ6 m;
    m.x_q6 = at.x_q6 + (int32_t)((int64_t)r * 64 * (n1.x_q15 + n2.x_q15) / denom_q15);
    m.y_q6 = at.y_q6 + (int32_t)((int64_t)r * 64 * (n1.y_q15 + n2.y_q15) / denom_q15);
    return emit_checked(at, m, out);
  }
  // Convex: arc from n1 to n2 about the corner, split at the bisector when over 90 deg.
  arc_center_ = at;
  arc_a_ = n1;
  if (dot_q30 < 0) {
    Unit mid;
    const int32_t sx = n1.x_q15 + n2.x_q15;
    const int32_t sy = n1.y_q15 + n2.y_q15;
    if (sx == 0 && sy == 0) {
      // Full reversal: go round the end, R * mid pointing along the old travel direction
      // (the travel direction is n1 rotated right).
      const Unit tu = left_normal(in_dir);
      mid.x_q15 = r > 0 ? tu.y_q15 : -tu.y_q15;
      mid.y_q15 = r > 0 ? -tu.x_q15 : tu.x_q15;
    } else {
      // Unit of (sx, sy): left_normal() of the vector rotated right.
      Direction rot;
      rot.dx = (int16_t)(sy / 4);
      rot.dy = (int16_t)(-sx / 4);
      mid = left_normal(rot);
    }
    arc_b_ = mid;
    arc_c_ = n2;
    arc_halves_left_ = 2;
  } else {
    arc_b_ = n2;
    arc_halves_left_ = 1;
  }
  // Points per half: chord error of an arc step phi is R phi^2 / 8 <= tol. A half is
  // <= 90 deg and its chord c = |a - b|; the normalised-lerp spacing is at most 1.3x the
  // even one, and the angle at most 1.11 c: steps = ceil(1.45 c sqrt(R / (8 tol))).
  const int64_t cx = (int64_t)arc_a_.x_q15 - arc_b_.x_q15;
  const int64_t cy = (int64_t)arc_a_.y_q15 - arc_b_.y_q15;
  const uint32_t c_q15 = isqrt32((uint32_t)(cx * cx + cy * cy));
  const uint32_t root_q8 = isqrt32((uint32_t)((r_abs << 16) / (8 * (int64_t)tol_um_)));
  int64_t steps = ((int64_t)c_q15 * 145 * root_q8) / ((int64_t)100 * 32768 * 256) + 1;
  if (steps > 256) steps = 256;
  arc_steps_ = (uint16_t)steps;
  arc_index_ = 1;
  return emit_checked(at, offset_point(at, n1), out);
}

// One point of the corner arc: the normalised blend of the half's two normals.
bool CurveWalker::arc_point(PointUm* out) {
  const int32_t k = arc_index_;
  const int32_t m = arc_steps_;
  Direction blend;
  const int32_t bx = ((m - k) * arc_a_.x_q15 + k * arc_b_.x_q15) / m;
  const int32_t by = ((m - k) * arc_a_.y_q15 + k * arc_b_.y_q15) / m;
  // left_normal() of the blend rotated right gives the unit blend itself.
  blend.dx = (int16_t)(by / 4);
  blend.dy = (int16_t)(-bx / 4);
  const Unit n = left_normal(blend);
  const PointQ6 p = offset_point(arc_center_, n);
  if (arc_index_ >= arc_steps_) {
    --arc_halves_left_;
    arc_index_ = 1;
    arc_a_ = arc_b_;
    arc_b_ = arc_c_;
  } else {
    ++arc_index_;
  }
  last_base_ = arc_center_;
  return emit_plain(p, out);
}

// Path point at t: the curve point, moved by the tool offset along the left normal.
PointQ6 CurveWalker::path_point(uint32_t t_q16, Direction* dir) {
  const PointQ6 base = eval_.evaluate_q6(t_q16);
  if (settings_.tool_offset_um == 0) return base;
  *dir = usable_direction(t_q16);
  if (is_zero(*dir)) *dir = last_dir_;
  return offset_point(base, left_normal(*dir));
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

// Unit left normal (-dy, dx) / |d| in Q15: one root and two 32/16 divisions (no 64-bit
// arithmetic: DIV.UD on the dsPIC).
CurveWalker::Unit CurveWalker::left_normal(const Direction& d) const {
  Unit u;
  const uint32_t s = mul_u16_u16((uint16_t)abs_u32(d.dx), (uint16_t)abs_u32(d.dx)) +
                     mul_u16_u16((uint16_t)abs_u32(d.dy), (uint16_t)abs_u32(d.dy));  // < 2^31
  if (s == 0) {
    u.x_q15 = 0;
    u.y_q15 = 32767;
    return u;
  }
  // |d| * 2^pre with 15 to 16 significant bits: the root of s * 4^pre in [2^30, 2^32)
  // (relative error below 2^-15; the former Newton-refined q8 length had 2^-13).
  uint32_t s4 = s;
  uint8_t pre = 0;
  while (s4 < (1UL << 30)) {
    s4 <<= 2;
    ++pre;
  }
  const uint16_t len = isqrt32(s4);  // in [2^15, 2^16)
  // component * 2^(15 + pre) / len: the Q15 value, a 32/16 division with a quotient
  // <= 2^15 (component <= |d|) and a dividend <= len * 2^15 < 2^31.
  const uint8_t up = (uint8_t)(15 + pre);
  const uint16_t ux = div_u32_u16(abs_u32(d.dy) << up, len, 0);
  const uint16_t uy = div_u32_u16(abs_u32(d.dx) << up, len, 0);
  u.x_q15 = d.dy > 0 ? -(int32_t)ux : (int32_t)ux;  // -dy / |d|, truncated toward zero
  u.y_q15 = d.dx < 0 ? -(int32_t)uy : (int32_t)uy;
  return u;
}

// base + R * normal, in q6: R * 64 < 2^23 times |normal| <= 2^15 as 16x16 products on the
// magnitudes (truncated toward zero, the sign applied after).
PointQ6 CurveWalker::offset_point(const PointQ6& base, const Unit& n) const {
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
    const int64_t bx = (int64_t)base.x_q6 - last_base_.x_q6;
    const int64_t by = (int64_t)base.y_q6 - last_base_.y_q6;
    const int64_t ox = (int64_t)p.x_q6 - last_out_.x_q6;
    const int64_t oy = (int64_t)p.y_q6 - last_out_.y_q6;
    if (bx * bx + by * by > 64 * 64 && bx * ox + by * oy < 0) {
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
