// Span setup (blossoming the De Boor triangle into Bezier points, then power basis) and
// per-point Horner evaluation in 32x16 fixed point.
#include "firmware/core/span_evaluator.h"

#include <string.h>  // memset

#include "firmware/core/divide.h"        // reciprocal_of, mul_reciprocal_q27
#include "firmware/core/wide_product.h"  // Wide, mul_wide

namespace core {

namespace {

// Homogeneous point used during setup: x, y in um * weight with 9 fraction bits
// (|.| < 2^32 for |coord| <= 1e6 relative and weight < 4), w in Q29 (< 2^31).
// Indexed (x, y, w) so that setup() loops over the coordinates: each 64-bit step is code
// once, not twice (64-bit arithmetic is long inline code on 8- and 16-bit cores).
struct Homog {
  int64_t v[3];
};

enum { kX = 0, kY = 1, kW = 2 };

// The setup's 64-bit helpers stay out of line (noinline): 64-bit arithmetic is long inline
// code on 8- and 16-bit cores, and the setup runs once per span in the background (on the
// AVR proxy the calls cost flash 1.6 kB less, the setup ~3 % more cycles).
enum { kSetupShift = 9, kAlphaShift = 29 };

// *b = a + alpha * (b - a) with alpha in Q29, rounded, in place (pointers and a 32-bit
// alpha: the arguments fit the registers, no 8-byte copies at the call). |b - a| < 2^33
// keeps the product < 2^62. alpha 0 and 1 (every De Boor level has one of each at the
// span's own knots) give a and b exactly, without the multiply.
__attribute__((noinline)) void lerp64(const int64_t* a, int64_t* b, int32_t alpha_q29) {
  if (alpha_q29 == 0) {
    *b = *a;
    return;
  }
  if (alpha_q29 == (1L << kAlphaShift)) return;
  *b = *a + (((*b - *a) * (int64_t)alpha_q29 + ((int64_t)1 << (kAlphaShift - 1))) >> kAlphaShift);
}

// v * 2^n without the undefined behaviour of shifting a negative value left.
int64_t shl64(int64_t v, uint8_t n) {
  return (int64_t)((uint64_t)v << n);  // two's complement (GCC on every target): v * 2^n
}

// (num / den) in Q29, rounded (halves up), for num <= den, den > 0: long division, a
// quotient bit a step in 32-bit words (den may fill 32 bits: the bit shifted out of the
// remainder is kept), no 64-bit division. num 0 and num = den (a blend at a knot of the
// span itself) need none at all. Always inline, like bezier_points and scale_direction
// below: each has one caller, and the three out of line were 0.2 kB more on the AVR proxy.
inline __attribute__((always_inline)) uint32_t ratio_q29(uint32_t num, uint32_t den) {
  if (num == 0) return 0;
  if (num == den) return 1UL << kAlphaShift;
  uint32_t rem = num;  // < den
  uint32_t q = 0;
  for (uint8_t i = 0; i < kAlphaShift; ++i) {
    const bool carry = (rem & 0x80000000UL) != 0;
    rem <<= 1;
    q <<= 1;
    if (carry || rem >= den) {
      rem -= den;  // 2 rem - den, in [0, den), modulo 2^32
      q |= 1U;
    }
  }
  // floor(num 2^29 / den) = q with remainder rem: + den / 2 before the floor adds 1 when
  // rem + floor(den / 2) >= den.
  return rem >= den - (den >> 1) ? q + 1U : q;
}

// round(num / d) for d > 0 (rounds half away from zero; d a weight in Q29, < 2^31). d = 2^29
// (every weight of a polynomial span) is a shift with the same value: polynomial spans
// share this code with rational ones and skip the 64-bit division.
__attribute__((noinline)) int64_t div_round(int64_t num, uint32_t d) {
  const uint64_t mag = num >= 0 ? (uint64_t)num : (uint64_t)-num;
  const uint64_t half_up = mag + (d >> 1);
  const uint64_t q = d == (1UL << kAlphaShift) ? half_up >> kAlphaShift : half_up / d;
  return num >= 0 ? (int64_t)q : -(int64_t)q;
}

// (v * w) >> 29 (floor) for a Q29 weight w < 2^31 and a 32-bit v (a 32x32 product), for
// w = 2^29 (polynomial spans) too: the exact v, and no branch beside the product (the
// three weight-1 shortcuts here were 158 B on the AVR proxy for ~8 % of a span setup's
// cycles, in the background).
__attribute__((noinline)) int64_t mul_weight_q29(int32_t v, uint32_t w_q29) {
  return ((int64_t)v * (int64_t)(int32_t)w_q29) >> kAlphaShift;
}

// rel * w_q14 / 2^5 truncated toward zero: a coordinate times its weight in q9 (weight 1:
// exactly rel * 2^9). Written through out (no 8-byte return value to copy at the call).
__attribute__((noinline)) void weighted_q9(int32_t rel, uint16_t w_q14, int64_t* out) {
  *out = (int64_t)rel * w_q14 / (1 << (14 - kSetupShift));
}

// v * (w_q29 >> 8), the products of the end tangent (w = 2^29: exactly v * 2^21).
__attribute__((noinline)) int64_t mul_weight_q21(int64_t v, uint32_t w_q29) {
  return v * (int64_t)(w_q29 >> 8);
}

// Coordinate i of a Bezier point in um * 2^extra_bits relative to the span's first control
// point, rounded: x / w (a shift for polynomial spans, whose w is 2^29 everywhere).
__attribute__((noinline)) uint32_t bezier_coordinate(const Homog& h, uint8_t i,
                                                     uint8_t extra_bits) {
  // The low 32 bits: all that the callers keep.
  return (uint32_t)div_round(shl64(h.v[i], (uint8_t)(kAlphaShift - kSetupShift + extra_bits)),
                             (uint32_t)h.v[kW]);
}

// The De Boor blend factors of one span: alpha[u][r-1][jj-1] = (u - knot[j]) /
// (knot[j+p+1-r] - knot[j]) in Q29 (<= 2^29) for u = knot[span] (0) and knot[span+1] (1),
// j = span - p + jj. Computed once per span: each blossom below uses the same ones. Every
// denominator covers the span: never zero.
struct Alphas {
  int32_t q29[2][kMaxDegree][kMaxDegree];
};

__attribute__((noinline)) void blend_factors(const Spline& s, uint16_t span, Alphas* a) {
  const uint8_t p = s.degree;
  for (uint8_t side = 0; side < 2; ++side) {
    // knot[j] <= u <= knot[j + p + 1 - r] (the window is in order): both differences are
    // below 2^32, exact as unsigned 32-bit ones.
    const uint32_t u = (uint32_t)s.knot[span + side];
    for (uint8_t r = 1; r <= p; ++r) {
      for (uint8_t jj = r; jj <= p; ++jj) {
        const uint16_t j = (uint16_t)(span - p + jj);  // control index of d[jj]
        const uint32_t lo = (uint32_t)s.knot[j];
        const uint32_t hi = (uint32_t)s.knot[j + p + 1 - r];
        a->q29[side][r - 1][jj - 1] = (int32_t)ratio_q29(u - lo, hi - lo);
      }
    }
  }
}

// One level r of De Boor's triangle in place, every blend at the knot of `side`.
void blossom_level(uint8_t p, bool rational, const Alphas& a, uint8_t side, uint8_t r, Homog* d) {
  const uint8_t coordinates = rational ? 3 : 2;
  for (uint8_t jj = p; jj >= r; --jj) {
    const int32_t alpha = a.q29[side][r - 1][jj - 1];
    for (uint8_t i = 0; i < coordinates; ++i) lerp64(&d[jj - 1].v[i], &d[jj].v[i], alpha);
  }
}

// The Bezier points b[0..p] of the span: b[k] is the blossom with k arguments equal to
// knot[span+1] (levels 1..k of the triangle) and p-k equal to knot[span] (levels k+1..p).
// The blossom is symmetric, so b[k] and b[k+1] share their first k levels: those are done
// once (16 level blends for a cubic instead of 24). Equal weights (a polynomial spline) stay
// equal: their blend is skipped.
// d0 may be b (it is read before b is written).
inline __attribute__((always_inline)) void bezier_points(uint8_t p, bool rational, const Alphas& a,
                                                         const Homog* d0, Homog* b) {
  Homog shared[kMaxDegree + 1];  // after k levels at knot[span+1]
  for (uint8_t j = 0; j <= p; ++j) shared[j] = d0[j];
  for (uint8_t k = 0; k <= p; ++k) {
    if (k > 0) blossom_level(p, rational, a, 1, k, shared);
    Homog d[kMaxDegree + 1];
    for (uint8_t j = 0; j <= p; ++j) d[j] = shared[j];
    for (uint8_t r = (uint8_t)(k + 1); r <= p; ++r) blossom_level(p, rational, a, 0, r, d);
    b[k] = d[p];
  }
}

// Power-basis coefficients of a degree-p Bezier polynomial with values b[0..p]:
// c[k] = C(p, k) times the k-th forward difference of b at 0 (binomials 1..3 as adds).
// The differences are taken in place in b (one loop). Only adds and subtracts: on the low
// 32 bits of the exact 64-bit values they give the low 32 bits of the exact result, which
// is all that is kept (|c[k]| < 2^31), so the arithmetic is 32-bit (wrapping, unsigned).
void power_basis(uint8_t p, uint32_t* b, int32_t* c) {
  c[0] = (int32_t)b[0];
  for (uint8_t k = 1; k <= kMaxDegree; ++k) {
    if (k > p) {
      c[k] = 0;
      continue;
    }
    for (uint8_t j = p; j >= k; --j) b[j] -= b[j - 1];
    // C(p, k): 1 at k = p, p at k = 1, 3 for (3, 2).
    const uint32_t v = b[k];
    c[k] = (int32_t)(k == p ? v : (k == 1 && p == 2 ? v + v : v + v + v));
  }
}

// Coefficients of one coordinate i (x or y, or the weight) from the Bezier points:
// numerators (x - w o) 2^26 / w_max rounded (w 2^27 / w_max), then the power basis. For x
// and y, o is the span start rounded to 1 um (written to *origin_um, absolute) and the span
// end (q6, absolute) goes to *end_q6. Out of line and per coordinate: the 64-bit
// temporaries stay in a small stack frame (on the AVR a frame above 63 bytes makes every
// spill five instructions).
__attribute__((noinline)) void coordinate_coefficients(const Homog* b, uint8_t p, uint8_t i,
                                                       int32_t ref_um, uint32_t w_max, int32_t* c,
                                                       int32_t* origin_um, int32_t* end_q6) {
  int32_t o_q9 = 0;  // |start| * 2^9 < 2^31
  uint8_t shift = kQ27Shift;
  if (i != kW) {
    const int32_t start_um = (int32_t)bezier_coordinate(b[0], i, 0);  // |.| < 2^22
    *origin_um = ref_um + start_um;
    *end_q6 = (int32_t)((uint32_t)ref_um * (1UL << kQ6Shift) +
                        (uint32_t)bezier_coordinate(b[p], i, kQ6Shift));
    o_q9 = (int32_t)((uint32_t)start_um << kSetupShift);
    shift = 26;
  }
  uint32_t n[kMaxDegree + 1];
  for (uint8_t k = 0; k <= p; ++k) {
    // x - w * o in um*w q9 (w in q29: x - o for polynomial spans).
    const int64_t r = b[k].v[i] - mul_weight_q29(o_q9, (uint32_t)b[k].v[kW]);
    // Rational: r * 2^29 / w_max is um*w_norm in q9; to q6: * 2^26 / w_max.
    n[k] = (uint32_t)div_round(shl64(r, shift), w_max);
  }
  power_basis(p, n, c);
}

// Horner in t (uq16; t_q16 = 65536 handled as 1.0 by the caller) over coefficients c of
// degree p <= kMaxDegree: one loop, one copy of the 32x16 product (unrolled per degree it
// was three chains, 0.2 kB more on the AVR proxy, for ~20 cycles a sum). One copy for every
// caller: inlined twice into evaluate_q6 it cost 0.6 kB of flash. A pointer walks down the
// coefficients: indexing by p recomputed the address every step.
int32_t horner(const int32_t* c, uint8_t p, uq16_t t) {
  const int32_t* pc = c + p;
  int32_t acc = *pc;
  while (pc != c) acc = *--pc + mul_32x16_uq16_round(acc, t);
  return acc;
}

// x and y of the polynomial point by Horner together: one call and one loop for both sums
// (two horner() calls cost ~70 cycles more per point, issue 9's budget of 911).
void horner_xy(const int32_t* cx, const int32_t* cy, uint8_t p, uq16_t t, PointQ6* r) {
  const int32_t* px = cx + p;
  const int32_t* py = cy + p;
  int32_t x = *px;
  int32_t y = *py;
  while (px != cx) {
    x = *--px + mul_32x16_uq16_round(x, t);
    y = *--py + mul_32x16_uq16_round(y, t);
  }
  r->x_q6 += x;
  r->y_q6 += y;
}

// Scales (x, y) so that the larger magnitude lies in [2^13, 2^14): a direction only.
// Exact wide components (the rational derivative, the span end): no 64-bit shifts or
// divisions; division by 2^shift truncates toward zero on the magnitude.
Direction scale_direction_wide(const Wide& x, const Wide& y) {
  Direction d = {0, 0};
  const Wide ax = wide_abs(x);
  const Wide ay = wide_abs(y);
  const uint8_t bits_x = wide_bit_length(ax);
  const uint8_t bits_y = wide_bit_length(ay);
  const uint8_t bits = bits_x > bits_y ? bits_x : bits_y;
  if (bits == 0) return d;
  // The larger magnitude into [2^13, 2^14): shifted right by bits - 14, or left.
  uint16_t rx;
  uint16_t ry;
  if (bits >= 14) {
    rx = (uint16_t)wide_shift_right_low(ax, (uint8_t)(bits - 14));
    ry = (uint16_t)wide_shift_right_low(ay, (uint8_t)(bits - 14));
  } else {
    rx = (uint16_t)(ax.lo << (14 - bits));
    ry = (uint16_t)(ay.lo << (14 - bits));
  }
  d.dx = wide_negative(x) ? (int16_t) - (int16_t)rx : (int16_t)rx;
  d.dy = wide_negative(y) ? (int16_t) - (int16_t)ry : (int16_t)ry;
  return d;
}

// The same for a 64-bit pair e[0], e[1] (the span setup; through a pointer: no 16 bytes
// of arguments to copy).
inline __attribute__((always_inline)) Direction scale_direction(const int64_t* e) {
  Wide w[2];
  for (uint8_t i = 0; i < 2; ++i) {
    w[i].hi = (uint32_t)((uint64_t)e[i] >> 32);
    w[i].lo = (uint32_t)e[i];
  }
  return scale_direction_wide(w[0], w[1]);
}

// The same for 32-bit components (the polynomial derivative): identical results, without
// 64-bit shifts and divisions (helper calls on 16-bit targets). Division by 2^shift
// truncates toward zero as above: the shift works on the magnitude.
Direction scale_direction32(int32_t x, int32_t y) {
  Direction d = {0, 0};
  const uint32_t ax = abs_u32(x);
  const uint32_t ay = abs_u32(y);
  uint32_t m = ax > ay ? ax : ay;
  if (m == 0) return d;
  uint8_t down = 0;
  uint8_t up = 0;
  while (m >= (1UL << 22)) {  // whole bytes first, then bits
    m >>= 8;
    down = (uint8_t)(down + 8);
  }
  while (m >= (1UL << 14)) {
    m >>= 1;
    ++down;
  }
  while (m < (1UL << 13)) {
    m <<= 1;
    ++up;
  }
  // |result| < 2^14 either way; up only when m < 2^13, so nothing overflows.
  const uint16_t rx = (uint16_t)(down ? ax >> down : ax << up);
  const uint16_t ry = (uint16_t)(down ? ay >> down : ay << up);
  d.dx = x < 0 ? (int16_t) - (int16_t)rx : (int16_t)rx;
  d.dy = y < 0 ? (int16_t) - (int16_t)ry : (int16_t)ry;
  return d;
}

// Direction of the last non-degenerate Bezier leg into b[p] (projected): the end tangent.
__attribute__((noinline)) Direction end_tangent(const Homog* b, uint8_t p) {
  Direction d = {0, 0};
  for (int8_t k = (int8_t)(p - 1); k >= 0 && d.dx == 0 && d.dy == 0; --k) {
    int64_t e[2];
    for (uint8_t i = 0; i < 2; ++i) {
      e[i] = mul_weight_q21(b[p].v[i], (uint32_t)b[k].v[kW]) -
             mul_weight_q21(b[k].v[i], (uint32_t)b[p].v[kW]);
    }
    d = scale_direction(e);
  }
  return d;
}

// The Bezier points of the span, homogeneous, relative to its first control point (out of
// line: the arrays of the blossom stay out of setup()'s frame). b holds the control points
// first: bezier_points() copies them before it writes b.
// Returns the largest weight of the points, b[k].w (1 at least: a divisor).
__attribute__((noinline)) uint32_t bezier_of_span(const Spline& spline, uint16_t span, Homog* b) {
  const uint8_t p = spline.degree;
  const ControlPoint* const c = &spline.control[span - p];
  for (uint8_t j = 0; j <= p; ++j) {
    const uint16_t w_q14 = spline.rational ? c[j].weight_q14 : kWeightOneQ14;
    // |c - ref| < 2^22 (coordinates within kMaxCoordinateUm, checked by setup()).
    weighted_q9(c[j].x_um - c[0].x_um, w_q14, &b[j].v[kX]);
    weighted_q9(c[j].y_um - c[0].y_um, w_q14, &b[j].v[kY]);
    b[j].v[kW] = (int64_t)w_q14 << (kAlphaShift - 14);
  }
  Alphas alphas;
  blend_factors(spline, span, &alphas);
  bezier_points(p, spline.rational, alphas, b, b);
  // Each b[k].w mixes weight_q14 << 15 (in [2^15, 2^31)).
  uint32_t w_max = 1;
  for (uint8_t k = 0; k <= p; ++k) {
    const uint32_t w = (uint32_t)b[k].v[kW];
    if (w > w_max) w_max = w;
  }
  return w_max;
}

}  // namespace

// First span with positive length at or after index degree.
uint16_t first_span(const Spline& spline) {
  return next_span(spline, (uint16_t)(spline.degree - 1));
}

// Skips zero-length spans (repeated knots).
uint16_t next_span(const Spline& spline, uint16_t span) {
  uint16_t i = (uint16_t)(span + 1);
  while (i < spline.control_count && spline.knot[i + 1] <= spline.knot[i]) ++i;
  return i < spline.control_count ? i : spline.control_count;
}

// All zero (degree 0: unset); plain data, so one memset rather than a store per member.
SpanEvaluator::SpanEvaluator() {
  memset(static_cast<void*>(this), 0, sizeof *this);
}

// Blossoms the span into Bezier points relative to its first control point, then stores
// span-relative power-basis coefficients (see the header for the formats).
GeometryError SpanEvaluator::setup(const Spline& spline, uint16_t span) {
  degree_ = 0;
  const uint8_t p = spline.degree;
  if (check_shape(spline) != GeometryError::kOk || span < p || span >= spline.control_count ||
      spline.knot[span + 1] <= spline.knot[span]) {
    return GeometryError::kKnotRangeEmpty;
  }
  // The window this span reads must be sound even if nobody validated the spline: no
  // zero or negative denominator, no zero weight, no coordinate beyond the headroom.
  GeometryError e = check_knot_order(spline, (uint16_t)(span - p), (uint16_t)(span + p + 1));
  if (e == GeometryError::kOk) e = check_points(spline, (uint16_t)(span - p), span);
  if (e != GeometryError::kOk) return e;
  const ControlPoint& ref = spline.control[span - p];
  Homog b[kMaxDegree + 1];
  const uint32_t w_max = bezier_of_span(spline, span, b);  // the largest b[k].w
  // Per coordinate: the origin (the span start rounded to 1 um, absolute), the end point
  // straight from the last Bezier point (exact up to setup rounding), and the numerators
  // relative to the origin in q6 with the weights normalised to max 1.
  // Straight into the members (evaluate_q6 below reads origin_q6_ and the coefficients, not
  // end_). Through locals, avr-gcc 5.4.0 miscompiled this call sequence once (docs/performance.md).
  coordinate_coefficients(b, p, kX, ref.x_um, w_max, cx_, &origin_.x_um, &end_.x_q6);
  coordinate_coefficients(b, p, kY, ref.y_um, w_max, cy_, &origin_.y_um, &end_.y_q6);
  coordinate_coefficients(b, p, kW, 0, w_max, cw_, 0, 0);
  origin_q6_.x_q6 = origin_.x_um * (1L << kQ6Shift);  // |.| < 2^26: once, not per point
  origin_q6_.y_q6 = origin_.y_um * (1L << kQ6Shift);
  degree_ = p;
  // Derivative coefficients k * c[k] keep as many fraction bits as their Horner sums
  // allow (|sum| <= sum of k |c[k]| < 2^31): full q6 for ordinary spans.
  // That sum, dsum, in 32 bits: dsum = 16 top + low with top = sum k (m >> 4) and
  // low = sum k (m & 15) (<= 90), and dsum >> s >= 2^30 exactly when
  // top + low / 16 >= 2^(26 + s) (64-bit code is long on 8- and 16-bit cores).
  uint32_t top = 0;
  uint8_t low = 0;
  for (uint8_t k = 1; k <= p; ++k) {
    const uint32_t ax = abs_u32(cx_[k]);
    const uint32_t ay = abs_u32(cy_[k]);
    const uint32_t aw = abs_u32(cw_[k]);
    uint32_t m = ax > ay ? ax : ay;
    if (spline.rational && aw > m) m = aw;
    for (uint8_t r = 0; r < k; ++r) {  // k m as adds
      top += m >> 4;
      low = (uint8_t)(low + (m & 15));
    }
  }
  top += low >> 4;
  dir_shift_ = 0;
  while (top >= (1UL << (26 + dir_shift_))) ++dir_shift_;
  rational_ = spline.rational;
  start_ = evaluate_q6(0);
  end_dir_ = end_tangent(b, p);
  return GeometryError::kOk;
}

// Horner on the span-relative coefficients: per coordinate `degree` 32x16 products.
PointQ6 SpanEvaluator::evaluate_q6(uint32_t t_q16) const {
  if (t_q16 >= kUq16One) return end_;
  if (rational_) return rational_q6((uq16_t)t_q16);
  const uq16_t t = (uq16_t)t_q16;
  PointQ6 r = origin_q6_;
  horner_xy(cx_, cy_, degree_, t, &r);
  return r;
}

// N(t) / W(t): W by Horner too, then one reciprocal of W (one 32/16 division and a Newton
// step) and four 16x16 products per coordinate instead of a 64/32 division each.
PointQ6 SpanEvaluator::rational_q6(uq16_t t) const {
  // W > 0: a convex combination of weights > 0 (<= 2^27, normalised at setup); rounding
  // can never make it 0, and reciprocal_of treats w <= 0 as 1 anyway.
  // The three sums through the out-of-line horner() (inlined, they made this function
  // 937 dsPIC instructions; a call costs a few cycles against ~2 500 for the point).
  const Reciprocal inv_w = reciprocal_of(horner(cw_, degree_, t));
  // x and y through one copy of the reciprocal product (two copies: ~0.3 kB more).
  const int32_t* const c[2] = {cx_, cy_};
  int32_t v[2];
  for (uint8_t i = 0; i < 2; ++i) v[i] = mul_reciprocal_q27(horner(c[i], degree_, t), inv_w);
  PointQ6 r;
  r.x_q6 = origin_q6_.x_q6 + v[0];
  r.y_q6 = origin_q6_.y_q6 + v[1];
  return r;
}

// dP/dt from the derivative polynomial (coefficients k * c[k]) at 2 fewer fraction bits.
Direction SpanEvaluator::direction(uq16_t t) const {
  if (degree_ == 0) {
    Direction z = {0, 0};
    return z;
  }
  const int32_t* const c[2] = {cx_, cy_};
  int32_t p[2];  // q(6 - dir_shift_) um
  for (uint8_t i = 0; i < 2; ++i) p[i] = derivative_at(c[i], t);
  if (!rational_) return scale_direction32(p[0], p[1]);
  // P = N / W, P' ~ N' W - N W' (W > 0 leaves the direction unchanged).
  const int32_t w1 = derivative_at(cw_, t);
  const int32_t w = horner(cw_, degree_, t);
  // p q(6-s); w q27; n q6; w1 q(27-s): both products in q(33-s) um, exact (held wide: no
  // 64-bit multiply). x and y through one loop: one copy of the wide products.
  Wide q[2];
  for (uint8_t i = 0; i < 2; ++i) {
    q[i] = wide_sub(mul_wide(p[i], w), mul_wide(horner(c[i], degree_, t), w1));
  }
  return scale_direction_wide(q[0], q[1]);
}

// a2 = h^2 (c2 + 3 c3 t0), a3 = h^3 c3: 32x16 products. dir_shift_ 0 means
// sum k |c[k]| < 2^30, so |c2| + 3 |c3| < 2^30 and nothing overflows.
bool SpanEvaluator::step_bend_q6(uint32_t t0_q16, uint32_t h_q16, PointQ6* a2, PointQ6* a3) const {
  if (rational_ || dir_shift_ != 0 || degree_ == 0 || t0_q16 >= kUq16One) return false;
  const int32_t* const c[2] = {cx_, cy_};
  // e = (a2.x, a2.y, a3.x, a3.y) before the powers of h: one loop, so the 32x16 product
  // is code twice instead of six times (-0.2 kB on the AVR proxy).
  int32_t e[4];
  for (uint8_t i = 0; i < 2; ++i) {
    const int32_t m = mul_32x16_uq16(c[i][3], (uq16_t)t0_q16);
    e[i] = c[i][2] + m + m + m;
    e[2 + i] = c[i][3];
  }
  if (h_q16 < kUq16One) {
    for (uint8_t j = 0; j < 4; ++j) {
      for (uint8_t k = j < 2 ? 2 : 3; k > 0; --k) e[j] = mul_32x16_uq16(e[j], (uq16_t)h_q16);
    }
  }
  a2->x_q6 = e[0];
  a2->y_q6 = e[1];
  a3->x_q6 = e[2];
  a3->y_q6 = e[3];
  return true;
}

// The derivative polynomial at t: its coefficients k c[k] >> dir_shift_ (times 1, 2, 3 as
// adds: a multiply by a variable k is a 32x32 library call on 16-bit targets; the shift
// usually 0), then Horner. The coefficients' array stays out of direction()'s frame.
__attribute__((noinline)) int32_t SpanEvaluator::derivative_at(const int32_t* c, uq16_t t) const {
  int32_t d[kMaxDegree];
  for (uint8_t k = 1; k <= degree_; ++k) {
    const int32_t v = dir_shift_ ? asr32(c[k], dir_shift_) : c[k];
    d[k - 1] = k == 1 ? v : (k == 2 ? v + v : v + v + v);
  }
  return horner(d, (uint8_t)(degree_ - 1), t);
}

}  // namespace core
