// Divisions the hot paths can afford: 32/16 with a 16-bit quotient (the dsPIC's DIV.UD,
// 18 cycles) and a reciprocal, found once with one such division and a Newton step, that
// turns every further division by the same value into four 16x16 products. No 64-bit
// arithmetic and no 32/32 division anywhere here.
#ifndef FIRMWARE_CORE_DIVIDE_H
#define FIRMWARE_CORE_DIVIDE_H

#include <stdint.h>  // uint32_t, uint16_t, int32_t

namespace core {

// floor(n / d) and n mod d for (n >> 16) < d (so the quotient fits 16 bits): one DIV.UD on
// the dsPIC, a 16-step shift-and-subtract on 16-bit halves elsewhere. rem may be null.
uint16_t div_u32_u16(uint32_t n, uint16_t d, uint16_t* rem);

// floor(n / d) for n < d * 2^bits, bits in 1..16: the quotient has at most `bits` bits, so
// the shift-and-subtract loop runs `bits` times only (DIV.UD on the dsPIC all the same).
uint16_t div_u32_u16_small(uint32_t n, uint16_t d, uint8_t bits);

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
Reciprocal reciprocal_of(int32_t w);

// round(x * 2^27 / w) for the w of r (the rational point's N / W, with W in Q27), within
// 1 + |result| * 2^-27 of the exact quotient. Bounds: w <= 2^28 and |x * 2^27 / w| < 2^29
// (|x| is clamped so that nothing overflows beyond them). Four 16x16 products.
int32_t mul_reciprocal_q27(int32_t x, const Reciprocal& r);

}  // namespace core

#endif  // FIRMWARE_CORE_DIVIDE_H
