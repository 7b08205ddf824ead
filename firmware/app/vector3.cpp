// Integer 3-vector normalisation and length (Crenshaw square root from the core).
#include "firmware/app/vector3.h"

#include "firmware/core/fixed_point.h"  // abs_u32
#include "firmware/core/isqrt.h"        // isqrt32

namespace app {

void normalise3(const int32_t d[3], int16_t out[3], int8_t* shift) {
  uint32_t m = core::abs_u32(d[0]);
  const uint32_t m1 = core::abs_u32(d[1]);
  const uint32_t m2 = core::abs_u32(d[2]);
  if (m1 > m) m = m1;
  if (m2 > m) m = m2;
  int8_t s = 0;
  if (m == 0) {
    out[0] = out[1] = out[2] = 0;
    *shift = 0;
    return;
  }
  while (m >= 32768UL) {
    m >>= 1;
    ++s;
  }
  while (m < 16384UL) {
    m <<= 1;
    --s;
  }
  for (uint8_t i = 0; i < 3; ++i) {
    // Rounded, so a long vector does not aim systematically beside its end point.
    int32_t v = s > 0 ? ((d[i] + ((int32_t)1 << (s - 1))) >> s) : (d[i] * ((int32_t)1 << -s));
    if (v > 32767) v = 32767;  // rounding up the largest component
    out[i] = (int16_t)v;
  }
  *shift = s;
}

uint16_t length3(const int16_t v[3]) {
  const uint32_t sum = (uint32_t)((int32_t)v[0] * v[0]) + (uint32_t)((int32_t)v[1] * v[1]) +
                       (uint32_t)((int32_t)v[2] * v[2]);
  return core::isqrt32(sum);
}

uint32_t scale_length_q4(uint16_t len, int8_t shift) {
  const int8_t s = (int8_t)(shift + 4);
  if (s >= 0) {
    if (s >= 15) return 1UL << 30;  // len < 2^15: anything shifted this far is "far"
    return (uint32_t)len << s;
  }
  if (s <= -16) return 0;
  return (uint32_t)len >> (-s);
}

}  // namespace app
