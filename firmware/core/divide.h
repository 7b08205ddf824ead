// Divisions the hot paths can afford: 32/16 with a 16-bit quotient (the dsPIC's DIV.UD,
// 18 cycles) and a reciprocal, found once with one such division and a Newton step, that
// turns every further division by the same value into four 16x16 products. No 64-bit
// arithmetic and no 32/32 division anywhere here.
#ifndef FIRMWARE_CORE_DIVIDE_H
#define FIRMWARE_CORE_DIVIDE_H

#include <stdint.h>  // uint32_t, uint16_t, int32_t

#include "firmware/core/fixed_point.h"  // mul_u16_u16, mul_s16_u16, high_half, low_half

namespace core {

// floor(n / d) and n mod d for (n >> 16) < d (so the quotient fits 16 bits): one DIV.UD on
// the dsPIC, a 16-step shift-and-subtract on 16-bit halves elsewhere. rem may be null.
uint16_t div_u32_u16(uint32_t n, uint16_t d, uint16_t* rem);

// The restoring division that stands in for DIV.UD where there is no divider (the AVR
// proxy): `steps` shift-and-subtract steps on acc = (remainder << 16) | dividend bits,
// the remainder's high half below d on entry; returns (remainder << 16) | quotient bits.
// Exposed so that the host tests check it although hosts divide in hardware.
// The remainder stays < d, so it fits 16 bits plus the bit shifted out at the top (carry).
// Inline: the loop is the whole of div_u32_u16 on the AVR.
inline __attribute__((always_inline)) uint32_t shift_subtract_divide(uint32_t acc, uint16_t d,
                                                                     uint8_t steps) {
  const uint32_t d_high = (uint32_t)d << 16;
  for (uint8_t i = 0; i < steps; ++i) {
    const bool carry = (acc & 0x80000000UL) != 0;
    acc <<= 1;
    if (carry || (uint16_t)(acc >> 16) >= d) {
      acc -= d_high;
      acc |= 1U;
    }
  }
  return acc;
}

// floor(n / d) for any n and d > 0 (d = 0 gives 0xFFFFFFFF): long division in two 16-bit
// digits, the first skipped when n < d * 2^16. rem may be null.
uint32_t div_u32_by_u16(uint32_t n, uint16_t d, uint16_t* rem);

// 1/w for w > 0 as  r_q62 / 2^(62 - shift):  r_q62 = 2^62 / (w * 2^shift), the normalised
// w * 2^shift in [2^30, 2^31), so r_q62 in (2^31, 2^32) (saturated at 2^32 - 1).
// Relative error below 2^-27 (docs/core-math.md, *Rational points*).
struct Reciprocal {
  uint32_t r_q62;
  uint8_t shift;  // 0..30
};

// Reciprocal of w (w <= 0 is treated as 1): one div_u32_u16 and four 16x16 products.
// Inline: once per rational point, on the per-point path.
inline __attribute__((always_inline)) Reciprocal reciprocal_of(int32_t w) {
  Reciprocal out;
  uint32_t wn = w > 0 ? (uint32_t)w : 1U;
  uint8_t s = 0;
  while (wn < (1UL << 23)) {  // bytes first: at most 3 steps, then at most 7 single bits
    wn <<= 8;
    s = (uint8_t)(s + 8);
  }
  while (wn < (1UL << 30)) {
    wn <<= 1;
    ++s;
  }
  // wn in [2^30, 2^31). Estimate from the top 16 bits: r0 ~ 2^46 / wn within 2^-15
  // (wh >= 2^15 > (2^31 - 1) >> 16, so the quotient fits 16 bits).
  const uint16_t wh = (uint16_t)((wn << 1) >> 16);  // wn >> 15, without a 15-step shift
  const uint16_t r0 = div_u32_u16(0x7FFFFFFFUL, wh, 0);
  // One Newton step r = r0 (2 - wn r0 / 2^46): p = wn r0 / 2^16 ~ 2^30, e = 2^30 - p
  // (|e| < 2^17), r_q62 = r0 2^16 + r0 e / 2^14. Error: (2^-15)^2 plus rounding, < 2^-27.
  const uint32_t p = (uint32_t)mul_s16_u16((int16_t)(wn >> 16), r0) +
                     (mul_u16_u16((uint16_t)wn, r0) >> 16);  // wn >> 16 < 2^15
  const int32_t e = (int32_t)((1UL << 30) - p);
  const int32_t corr = mul_32x16_uq16(e, r0) * 4;  // |.| < 2^18
  const uint32_t base = (uint32_t)r0 << 16;
  if (corr > 0 && base > 0xFFFFFFFFUL - (uint32_t)corr) {
    out.r_q62 = 0xFFFFFFFFUL;  // 2^62 / 2^30: one unit short, relative 2^-32
  } else {
    out.r_q62 = corr >= 0 ? base + (uint32_t)corr : base - (uint32_t)-corr;
  }
  out.shift = s;
  return out;
}

// round(x * 2^27 / w) for the w of r (the rational point's N / W, with W in Q27), within
// 1 + |result| * 2^-27 of the exact quotient. Bounds: w <= 2^28 and |x * 2^27 / w| < 2^29
// (|x| is clamped so that nothing overflows beyond them). Four 16x16 products.
// Inline: called twice per rational point, on the per-point path.
inline __attribute__((always_inline)) int32_t mul_reciprocal_q27(int32_t x, const Reciprocal& r) {
  // x * 2^27 / w = (x * 2^(shift - 3)) * r_q62 / 2^32 with w * 2^shift = wn in [2^30, 2^31).
  // |xs| = |x 2^27 / w| * wn / 2^30 < 2 |result|: clamped to 2^30 so hi below stays 15-bit.
  const int32_t kLimit = 1L << 30;
  int32_t xs;
  if (r.shift >= 3) {
    const uint8_t up = (uint8_t)(r.shift - 3);
    const int32_t room = kLimit >> up;
    if (x >= room) {
      xs = kLimit;
    } else if (x <= -room) {
      xs = -kLimit;
    } else {
      xs = (int32_t)((uint32_t)x << up);  // |x| < room: exact, no multiply
    }
  } else {
    xs = x >> (3 - r.shift);  // w >= 2^28: outside the bound, no overflow
  }
  // xs * r / 2^32, rounded, from four 16x16 products (xs = xh 2^16 + xl, r = rh 2^16 + rl).
  const int16_t xh = high_half(xs);  // |xh| <= 2^14
  const uint16_t xl = low_half(xs);
  const uint16_t rh = (uint16_t)(r.r_q62 >> 16);
  const uint16_t rl = (uint16_t)r.r_q62;
  // xl rh + (xl rl >> 16) <= (2^16 - 1)^2 + 2^16 - 1 < 2^32.
  const uint32_t u = mul_u16_u16(xl, rh) + (mul_u16_u16(xl, rl) >> 16);
  // |xh rl| <= 2^14 (2^16 - 1); plus u's low half and the rounding bit: < 2^31.
  const int32_t t = mul_s16_u16(xh, rl) + (int32_t)(u & 0xFFFFU) + 0x8000L;
  return mul_s16_u16(xh, rh) + (int32_t)(u >> 16) + (t >> 16);
}

}  // namespace core

#endif  // FIRMWARE_CORE_DIVIDE_H
