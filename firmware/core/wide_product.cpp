// Exact wide products from 16x16 products, and the carries that go with them.
#include "firmware/core/wide_product.h"

#include "firmware/core/fixed_point.h"  // mul_u16_u16, mul_s16_u16, high_half, low_half

namespace core {

namespace {

// The signed 16x16 product kept 16x16 (see opaque_s16 in fixed_point.h).
inline int32_t mul_s16_s16(int16_t a, int16_t b) {
  return (int32_t)opaque_s16(a) * opaque_s16(b);
}

Wide negate(const Wide& a) {
  Wide r;
  r.lo = ~a.lo + 1U;
  r.hi = ~a.hi + (r.lo == 0 ? 1U : 0U);
  return r;
}

// ua * ub exactly: inline in mul_wide, which the firmware calls (mul_wide_u, unused there,
// is left out of the image; the call between the two was 0.1 kB on the AVR proxy).
inline __attribute__((always_inline)) Wide magnitude_product(uint32_t ua, uint32_t ub) {
  const uint16_t ah = (uint16_t)(ua >> 16);
  const uint16_t al = (uint16_t)ua;
  const uint16_t bh = (uint16_t)(ub >> 16);
  const uint16_t bl = (uint16_t)ub;
  // Schoolbook in 16-bit digits: the sum at bit 16 (the low product's high half and the
  // middle products' low halves, < 3 * 2^16) carries into the high word without compares.
  const uint32_t low = mul_u16_u16(al, bl);
  const uint32_t mid_a = mul_u16_u16(ah, bl);
  const uint32_t mid_b = mul_u16_u16(al, bh);
  const uint32_t mid = (low >> 16) + (uint16_t)mid_a + (uint16_t)mid_b;
  Wide r;
  r.lo = (mid << 16) | (uint16_t)low;
  r.hi = mul_u16_u16(ah, bh) + (mid_a >> 16) + (mid_b >> 16) + (mid >> 16);
  return r;
}

}  // namespace

Wide mul_wide(int32_t a, int32_t b) {
  const Wide r = magnitude_product(abs_u32(a), abs_u32(b));
  return ((a < 0) != (b < 0)) ? negate(r) : r;
}

Wide mul_wide_u(uint32_t ua, uint32_t ub) {
  return magnitude_product(ua, ub);
}

Wide wide_add(const Wide& a, const Wide& b) {
  Wide r;
  r.lo = a.lo + b.lo;
  r.hi = a.hi + b.hi + (r.lo < a.lo ? 1U : 0U);
  return r;
}

Wide wide_sub(const Wide& a, const Wide& b) {
  return wide_add(a, negate(b));
}

Wide wide_abs(const Wide& a) {
  return wide_negative(a) ? negate(a) : a;
}

uint8_t wide_bit_length(const Wide& a) {
  uint32_t v = a.hi;
  uint8_t base = 32;
  if (v == 0) {
    v = a.lo;
    base = 0;
  }
  uint8_t n = 0;
  while (v >= (1UL << 8)) {  // whole bytes first, then bits
    v >>= 8;
    n = (uint8_t)(n + 8);
  }
  while (v != 0) {
    v >>= 1;
    ++n;
  }
  return n == 0 ? 0 : (uint8_t)(base + n);
}

uint32_t wide_shift_right_low(const Wide& a, uint8_t shift) {
  if (shift == 0) return a.lo;
  if (shift >= 32) return shift >= 64 ? 0 : a.hi >> (shift - 32);
  return (a.lo >> shift) | (a.hi << (32 - shift));
}

int32_t mul_q30(int32_t a, int32_t b) {
  const int16_t ah = high_half(a);  // |ah| < 2^14
  const uint16_t al = low_half(a);
  const int16_t bh = high_half(b);
  const uint16_t bl = low_half(b);
  // a b = ah bh 2^32 + (ah bl + al bh) 2^16 + al bl; the middle sum < 2^31 in magnitude.
  // Its floor / 2^14 as 4 * (its high half) + (its low half) / 2^14, and al bl / 2^30 from
  // its top byte: whole-byte moves (a 32-bit shift by 14 or 30 is a bit loop on the AVR).
  const int32_t mid = mul_s16_u16(ah, bl) + mul_s16_u16(bh, al);
  const uint8_t low_top = (uint8_t)(mul_u16_u16(al, bl) >> 24);
  const int32_t high = mul_s16_s16(ah, bh) + high_half(mid);  // |.| < 2^29
  return high * 4 + (int32_t)((low_half(mid) >> 14) + (low_top >> 6));
}

}  // namespace core
