// Crenshaw's integer square root: one result bit per iteration, shifts and subtracts only.
#include "firmware/core/isqrt.h"

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

}  // namespace core
