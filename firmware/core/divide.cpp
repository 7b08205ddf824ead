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

}  // namespace core
