// Corner arc normals and the unit left normal (see corner_arc.h).
#include "firmware/core/corner_arc.h"

#include "firmware/core/divide.h"        // div_u32_u16, div_u32_by_u16
#include "firmware/core/fixed_point.h"   // abs_u32, mul_u16_u16
#include "firmware/core/isqrt.h"         // isqrt32
#include "firmware/core/wide_product.h"  // mul_wide, wide_shift_right_low

namespace core {

namespace {

// (wa * a + wb * b) / m truncated toward zero, for |a|, |b| <= 2^15 and wa + wb = m <= 256:
// the quotient's magnitude <= 2^15, a 32/16 division.
int32_t blend_q15(int32_t wa, int32_t a, int32_t wb, int32_t b, uint16_t m) {
  const int32_t num = wa * a + wb * b;  // |.| <= 2^23
  const int32_t q = (int32_t)div_u32_u16(abs_u32(num), m, 0);
  return num < 0 ? -q : q;
}

}  // namespace

// A shift, not the 32/32 division avr-gcc -Os calls for a signed / 4.
int16_t quarter_toward_zero(int32_t v) {
  return v < 0 ? (int16_t) - (int16_t)(abs_u32(v) >> 2) : (int16_t)(v >> 2);
}

// No 64-bit arithmetic: DIV.UD on the dsPIC. The left normal (-dy, dx) made unit, its two
// components through one loop (written out per component: 0.1 kB more on the AVR proxy).
UnitQ15 left_unit_normal(const Direction& d) {
  const int32_t comp[2] = {-(int32_t)d.dy, d.dx};
  uint16_t mag[2];
  uint32_t s = 0;  // < 2^31
  for (uint8_t i = 0; i < 2; ++i) {
    mag[i] = (uint16_t)abs_u32(comp[i]);
    s += mul_u16_u16(mag[i], mag[i]);
  }
  UnitQ15 u;
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
  // <= 2^15 (component <= |d|) and a dividend <= len * 2^15 < 2^31; truncated toward zero.
  const uint8_t up = (uint8_t)(15 + pre);
  int32_t q[2];
  for (uint8_t i = 0; i < 2; ++i) {
    const int32_t v = div_u32_u16((uint32_t)mag[i] << up, len, 0);
    q[i] = comp[i] < 0 ? -v : v;
  }
  u.x_q15 = q[0];
  u.y_q15 = q[1];
  return u;
}

// Split at the bisector when over 90 degrees. Points per half: chord error of an arc step
// phi is R phi^2 / 8 <= tol. A half is <= 90 deg and its chord c = |a - b|; the
// normalised-lerp spacing is at most 1.3x the even one, and the angle at most 1.11 c:
// steps = ceil(1.45 c sqrt(R / (8 tol))). (A half is <= 90 degrees: c^2 <= 2^31.)
// r 2^16 / (8 tol) = r 2^13 / tol, and the steps' division by 100 2^23 is a shift and a
// 32/16 division: the same floors.
void CornerArc::begin(const PointQ6& center, const UnitQ15& n1, const UnitQ15& n2, bool over_90,
                      bool left_offset, uint32_t r_abs_um, uint16_t tol_um) {
  center_ = center;
  a_ = n1;
  b_ = n2;
  c_ = n2;
  halves_left_ = 1;
  if (over_90) {
    const int32_t sx = n1.x_q15 + n2.x_q15;
    const int32_t sy = n1.y_q15 + n2.y_q15;
    if (sx == 0 && sy == 0) {
      // Full reversal: go round the end, R * mid pointing along the old travel direction
      // (the travel direction is n1 rotated right).
      b_.x_q15 = left_offset ? n1.y_q15 : -n1.y_q15;
      b_.y_q15 = left_offset ? -n1.x_q15 : n1.x_q15;
    } else {
      // Unit of (sx, sy): left_unit_normal() of the vector rotated right.
      Direction rot;
      rot.dx = quarter_toward_zero(sy);
      rot.dy = quarter_toward_zero(-sx);
      b_ = left_unit_normal(rot);
    }
    halves_left_ = 2;
  }
  const uint32_t cx = (uint32_t)(a_.x_q15 - b_.x_q15);
  const uint32_t cy = (uint32_t)(a_.y_q15 - b_.y_q15);
  const uint32_t c_q15 = isqrt32(cx * cx + cy * cy);
  const uint32_t root_q8 = isqrt32(div_u32_by_u16(r_abs_um << 13, tol_um, 0));
  const Wide spread = mul_wide((int32_t)(c_q15 * 145), (int32_t)root_q8);  // < 2^39
  uint32_t steps = div_u32_by_u16(wide_shift_right_low(spread, 23), 100, 0) + 1;
  if (steps > 256) steps = 256;
  steps_ = (uint16_t)steps;
  index_ = 1;
}

UnitQ15 CornerArc::next_normal() {
  const int32_t k = index_;
  const int32_t m = steps_;
  const int32_t bx = blend_q15(m - k, a_.x_q15, k, b_.x_q15, (uint16_t)m);
  const int32_t by = blend_q15(m - k, a_.y_q15, k, b_.y_q15, (uint16_t)m);
  // left_unit_normal() of the blend rotated right gives the unit blend itself.
  Direction blend;
  blend.dx = quarter_toward_zero(by);
  blend.dy = quarter_toward_zero(-bx);
  if (index_ >= steps_) {
    --halves_left_;
    index_ = 1;
    a_ = b_;
    b_ = c_;
  } else {
    ++index_;
  }
  return left_unit_normal(blend);
}

}  // namespace core
