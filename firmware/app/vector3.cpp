// Integer 3-vector normalisation and length (Crenshaw square root from the core).
#include "firmware/app/vector3.h"

#include "firmware/core/fixed_point.h"  // abs_u32, asr32, mul_u16_u16
#include "firmware/core/isqrt.h"        // isqrt32

namespace app {

void normalise3(const int32_t d[3], int16_t out[3], int8_t* shift) {
  uint32_t m = core::abs_u32(d[0]);
  const uint32_t m1 = core::abs_u32(d[1]);
  const uint32_t m2 = core::abs_u32(d[2]);
  if (m1 > m) m = m1;
  if (m2 > m) m = m2;
  if (m == 0) {
    out[0] = out[1] = out[2] = 0;
    *shift = 0;
    return;
  }
  int8_t s = 0;
  if (m < 16384UL) {
    // Every component fits 15 bits: scale up in 16-bit arithmetic, exactly.
    uint16_t m16 = (uint16_t)m;
    while (m16 < 16384U) {
      m16 = (uint16_t)(m16 << 1);
      ++s;
    }
    for (uint8_t i = 0; i < 3; ++i) out[i] = (int16_t)(uint16_t)((uint16_t)d[i] << s);
    *shift = (int8_t)-s;
    return;
  }
  while (m >= (32768UL << 8)) {  // whole bytes first (byte moves), then single bits
    m >>= 8;
    s = (int8_t)(s + 8);
  }
  while (m >= 32768UL) {
    m >>= 1;
    ++s;
  }
  for (uint8_t i = 0; i < 3; ++i) {
    // round(d / 2^s) = ((d >> (s - 1)) + 1) >> 1, so a long vector does not aim
    // systematically beside its end point.
    int32_t v = s > 0 ? (core::asr32(d[i], (uint8_t)(s - 1)) + 1) >> 1 : d[i];
    if (v > 32767) v = 32767;  // rounding up the largest component
    out[i] = (int16_t)v;
  }
  *shift = s;
}

uint32_t sum_squares3(const int16_t v[3]) {
  uint32_t sum = 0;
  for (uint8_t i = 0; i < 3; ++i) {
    const uint16_t a = (uint16_t)(v[i] < 0 ? -(int32_t)v[i] : v[i]);  // <= 2^15
    sum += core::mul_u16_u16(a, a);  // unsigned 16x16: the cheaper multiply
  }
  return sum;
}

uint16_t length3(const int16_t v[3]) {
  return core::isqrt32(sum_squares3(v));
}

bool length_q4_exceeds(uint32_t sum_sq, int8_t shift, uint32_t limit_q4) {
  const int8_t s = (int8_t)(shift + 4);
  if (s >= 15) return (1UL << 30) > limit_q4;  // scale_length_q4 saturates there
  if (s <= -16) return false;                  // and is 0 there
  // Smallest len with scale_length_q4(len, shift) > limit_q4.
  uint32_t threshold;
  if (s >= 0) {
    threshold = (limit_q4 >> s) + 1U;  // len << s > limit
  } else {
    if (limit_q4 >= 65535UL) return false;  // len >> -s <= 56755 never exceeds it
    threshold = (limit_q4 + 1U) << -s;      // len >> -s > limit
  }
  if (threshold > 65535UL) return false;  // len < 2^16
  // floor(sqrt(sum_sq)) >= threshold  <=>  sum_sq >= threshold^2
  return sum_sq >= core::mul_u16_u16((uint16_t)threshold, (uint16_t)threshold);
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
