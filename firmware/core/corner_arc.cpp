// Corner arc normals and the unit left normal (see corner_arc.h).
#include "firmware/core/corner_arc.h"

#include "firmware/core/divide.h"       // div_u32_u16
#include "firmware/core/fixed_point.h"  // abs_u32, mul_u16_u16
#include "firmware/core/isqrt.h"        // isqrt32

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

// No 64-bit arithmetic: DIV.UD on the dsPIC.
UnitQ15 left_unit_normal(const Direction& d) {
  UnitQ15 u;
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

void CornerArc::start(const PointQ6& center, const UnitQ15& a, const UnitQ15& b, const UnitQ15& c,
                      uint8_t halves, uint16_t steps) {
  center_ = center;
  a_ = a;
  b_ = b;
  c_ = c;
  halves_left_ = halves;
  steps_ = steps;
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
