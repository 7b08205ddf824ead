// Exact 32x32 -> 64-bit products held as two 32-bit halves, and the few things the per-point
// paths do with them (sign of a sum, difference, leading bit, a shifted slice), built from
// 16x16 products: no 64-bit helper call (___muldi3 on the dsPIC, __muldi3 on the AVR).
#ifndef FIRMWARE_CORE_WIDE_PRODUCT_H
#define FIRMWARE_CORE_WIDE_PRODUCT_H

#include <stdint.h>  // uint32_t, int32_t, uint8_t

#include "firmware/core/fixed_point.h"  // mul_u16_u16, abs_u32

namespace core {

// A signed 64-bit value in two's complement: value = hi * 2^32 + lo.
struct Wide {
  uint32_t hi;
  uint32_t lo;
};

// a * b exactly (any int32 operands): four 16x16 products on the magnitudes, sign after.
Wide mul_wide(int32_t a, int32_t b);

// a * b exactly for unsigned operands (the magnitude part of mul_wide).
Wide mul_wide_u(uint32_t a, uint32_t b);

// a - b and a + b (two's complement, exact while the result fits 64 bits).
Wide wide_sub(const Wide& a, const Wide& b);
Wide wide_add(const Wide& a, const Wide& b);

inline bool wide_negative(const Wide& a) {
  return (a.hi & 0x80000000UL) != 0;
}

// |a| (for a > -2^63).
Wide wide_abs(const Wide& a);

// Number of significant bits of a non-negative value (0 for 0).
uint8_t wide_bit_length(const Wide& a);

// floor(a / 2^shift) of a non-negative value, the low 32 bits of it (shift 0..63).
uint32_t wide_shift_right_low(const Wide& a, uint8_t shift);

// round-toward-minus-infinity a * b / 2^30 for |a|, |b| < 2^30: four 16x16 products and no
// 64-bit intermediate (error: the exact floor minus at most 1).
int32_t mul_q30(int32_t a, int32_t b);

}  // namespace core

#endif  // FIRMWARE_CORE_WIDE_PRODUCT_H
