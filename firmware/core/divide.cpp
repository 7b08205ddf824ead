// 32/16 division, long division by a 16-bit divisor, and the Newton reciprocal.
#include "firmware/core/divide.h"

#include "firmware/core/fixed_point.h"  // mul_u16_u16, mul_s16_u16, high_half, low_half

namespace core {

uint16_t div_u32_u16(uint32_t n, uint16_t d, uint16_t* rem) {
#if defined(__XC16__) || defined(__C30__)
  // DIV.UD (REPEAT #17): quotient and remainder of a 32/16 division.
  const uint16_t q = __builtin_divud(n, d);
  if (rem) *rem = (uint16_t)(n - (uint32_t)q * d);
  return q;
#elif defined(__AVR__)
  // No divider: 16 shift-and-subtract steps (not libgcc's 32-step 32/32 __udivmodsi4).
  const uint32_t acc = shift_subtract_divide(n, d, 16);
  if (rem) *rem = (uint16_t)(acc >> 16);
  return (uint16_t)acc;
#else
  // Hosts (the simulator, the tests) divide in hardware.
  if (rem) *rem = (uint16_t)(n % d);
  return (uint16_t)(n / d);
#endif
}

uint16_t div_u32_u16_small(uint32_t n, uint16_t d, uint8_t bits) {
#if defined(__XC16__) || defined(__C30__)
  (void)bits;
  return __builtin_divud(n, d);
#elif !defined(__AVR__)
  (void)bits;
  return (uint16_t)(n / d);  // hosts divide in hardware
#else
  // Pre-aligned: n << (16 - bits) still fits 32 bits (n < d 2^bits <= 2^(16 + bits)), its
  // top half stays below d, and its low 16 - bits bits are zero, so after `bits` steps the
  // low half holds the quotient alone.
  return (uint16_t)shift_subtract_divide(n << (16 - bits), d, bits);
#endif
}

uint32_t div_u32_by_u16(uint32_t n, uint16_t d, uint16_t* rem) {
  if (d == 0) {
    if (rem) *rem = 0;
    return 0xFFFFFFFFUL;
  }
  uint16_t hi = (uint16_t)(n >> 16);
  uint16_t q_hi = 0;
  if (hi >= d) q_hi = div_u32_u16(hi, d, &hi);  // hi < 2^16 <= d * 2^16: fits
  // hi < d now: the low digit fits 16 bits.
  const uint16_t q_lo = div_u32_u16(((uint32_t)hi << 16) | (uint16_t)n, d, rem);
  return ((uint32_t)q_hi << 16) | q_lo;
}

Reciprocal reciprocal_of(int32_t w) {
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
  const int32_t corr = mul_32x16_uq16(e, r0) * 4;  // |.| < 2^19
  const uint32_t base = (uint32_t)r0 << 16;
  if (corr > 0 && base > 0xFFFFFFFFUL - (uint32_t)corr) {
    out.r_q62 = 0xFFFFFFFFUL;  // 2^62 / 2^30: one unit short, relative 2^-32
  } else {
    out.r_q62 = corr >= 0 ? base + (uint32_t)corr : base - (uint32_t)-corr;
  }
  out.shift = s;
  return out;
}

int32_t mul_reciprocal_q27(int32_t x, const Reciprocal& r) {
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
