// Crenshaw's integer square root: one result bit per iteration, shifts and subtracts only.
#include "firmware/core/isqrt.h"

#include "firmware/core/divide.h"       // div_u32_u16
#include "firmware/core/fixed_point.h"  // mul_u16_u16

namespace core {

// Classic "abacus" form: bit walks down the even powers of four; remainder shrinks as
// each result bit is accepted. Equivalent to Crenshaw's formulation (Embedded Systems
// Programming, 1998): root doubles and the trial subtrahend is (root << 1 | 1) << 2k.
uint16_t isqrt32(uint32_t n) {
  uint32_t remainder = n;
  uint32_t root = 0;
  uint32_t bit = (uint32_t)1 << 30;  // highest power of four in 32 bits
  while (bit > remainder) bit >>= 2;
  while (bit != 0) {
    if (remainder >= root + bit) {
      remainder -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return (uint16_t)root;
}

uint16_t isqrt32_from(uint32_t n, uint16_t guess) {
  if (guess == 0) return isqrt32(n);
  const uint32_t g2 = mul_u16_u16(guess, guess);
  const bool below = g2 <= n;
  const uint32_t diff = below ? n - g2 : g2 - n;
  // Guess within about 1/512 of the root, and the correction (n - g^2) / 2g, which is then
  // below sqrt(n) / 512 + 1 < 2^8, computed as an 8-bit quotient (diff / 2) / g. (Shifts
  // by whole bytes only: a cheap byte move where a multi-bit shift is a loop.)
  if (diff > (n >> 8) || (diff >> 1) >= ((uint32_t)guess << 8)) return isqrt32(n);
  const uint16_t step = div_u32_u16_small(diff >> 1, guess, 8);
  if (!below && step > guess) return isqrt32(n);
  uint32_t x = below ? (uint32_t)guess + step : (uint32_t)guess - step;
  // Newton's step overshoots by (step / g)^2 g / 2 < 1, the floors and halving add 1 or 2:
  // walk the last units, with products only; a longer walk falls back (never happens).
  for (uint8_t k = 0; x > 65535UL || mul_u16_u16((uint16_t)x, (uint16_t)x) > n; ++k) {
    if (k == 3) return isqrt32(n);
    --x;
  }
  for (uint8_t k = 0; x < 65535UL && mul_u16_u16((uint16_t)(x + 1), (uint16_t)(x + 1)) <= n; ++k) {
    if (k == 3) return isqrt32(n);
    ++x;
  }
  return (uint16_t)x;
}

}  // namespace core
