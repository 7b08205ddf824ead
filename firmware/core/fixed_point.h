// Fixed-point formats of the geometry core and the few multiply/round/saturate helpers
// that every per-point path uses. Units are in the type and variable names.
#ifndef FIRMWARE_CORE_FIXED_POINT_H
#define FIRMWARE_CORE_FIXED_POINT_H

#include <stdint.h>  // int32_t, uint16_t

namespace core {

// Formats (value = raw / 2^fraction_bits):
//   q15_t      signed Q1.15, [-1, 1)            unit vectors, cosines
//   uq16_t     unsigned Q0.16, [0, 1)           curve parameter inside a knot span
//   q16_16_t   signed Q16.16, [-32768, 32768)   general ratios
//   q6_um_t    signed micrometres with 6 fraction bits, |v| < 33 554 432 um (33.5 m):
//              span-relative polynomial coefficients (see span_evaluator.h)
//   q27_t      signed Q4.27, |v| < 16           normalised rational weights
//   q14_weight unsigned Q2.14, (0, 4)           weights as stored (spline.h)
// Coordinates are int32_t micrometres (_um), |v| <= kMaxCoordinateUm (1e6).
typedef int16_t q15_t;
typedef uint16_t uq16_t;
typedef int32_t q16_16_t;
typedef int32_t q6_um_t;
typedef int32_t q27_t;

enum { kQ6Shift = 6, kQ27Shift = 27 };
static const q15_t kQ15Max = 32767;
static const uint32_t kUq16One = 65536UL;  // 1.0 in UQ0.16 (needs 17 bits)

// v unchanged, through an empty asm (no instruction on any target): keeps the optimiser
// from folding a 16-bit operand back into the 32-bit value it was cut from, which makes
// avr-gcc multiply 32x32 (__mulsi3, ~70 cycles) instead of 16x16 (__umulhisi3, ~25).
inline uint16_t opaque_u16(uint16_t v) {
  __asm__("" : "+r"(v));
  return v;
}
inline int16_t opaque_s16(int16_t v) {
  __asm__("" : "+r"(v));
  return v;
}

// The two 16x16 -> 32 products every 32x16 product is built from (one MUL each on the
// dsPIC; __umulhisi3 / __usmulhisi3 on the AVR, kept so by the barriers above).
inline uint32_t mul_u16_u16(uint16_t a, uint16_t b) {
  return (uint32_t)opaque_u16(a) * opaque_u16(b);
}
inline int32_t mul_s16_u16(int16_t a, uint16_t b) {
  return (int32_t)opaque_s16(a) * opaque_u16(b);  // |.| < 2^31
}

// The signed high and unsigned low halves of a 32-bit value: a = hi * 2^16 + lo.
inline int16_t high_half(int32_t a) {
  return (int16_t)((uint32_t)a >> 16);  // modulo conversion (GCC on every target)
}
inline uint16_t low_half(int32_t a) {
  return (uint16_t)a;
}

// (a * b) >> 16 for a signed 32-bit value and an unsigned Q0.16 fraction, rounded toward
// minus infinity. Exact (same result as a 64-bit product) but built from two 16x16
// products: a = hi * 2^16 + lo, so a * b >> 16 = hi * b + (lo * b >> 16).
// Never overflows: |result| <= |a|. One out-of-line copy (noinline), like asr32 below.
inline __attribute__((noinline)) int32_t mul_32x16_uq16(int32_t a, uq16_t b) {
  return mul_s16_u16(high_half(a), b) + (int32_t)(mul_u16_u16(low_half(a), b) >> 16);
}

// round(a * b / 2^16) (ties up): the same two products plus one add. Exact; |result| <= |a|.
inline int32_t mul_32x16_uq16_round(int32_t a, uq16_t b) {
  // lo * b + 2^15 <= (2^16 - 1)^2 + 2^15 < 2^32: no carry lost.
  return mul_s16_u16(high_half(a), b) + (int32_t)((mul_u16_u16(low_half(a), b) + 0x8000UL) >> 16);
}

// round(a * b / 2^15) for a signed 32-bit value and a Q15 fraction (ties up).
// Exact, from two 16x16 products; the caller keeps |a * b / 2^15| < 2^31.
inline int32_t mul_32x16_q15(int32_t a, q15_t b) {
  const int16_t hi = (int16_t)(a >> 16);
  const uint16_t lo = (uint16_t)(a & 0xFFFF);
  const int32_t hi_part = (int32_t)hi * (int32_t)b;  // hi * b
  const int32_t lo_part = (int32_t)((uint32_t)lo * (uint32_t)(b < 0 ? -(int32_t)b : (int32_t)b));
  // lo * b with the sign applied after the unsigned product (lo < 2^16, |b| <= 2^15).
  const int32_t lo_signed = b < 0 ? -lo_part : lo_part;
  // hi*b*2^16/2^15 = hi*b*2 is exact; only the low part needs rounding.
  return hi_part * 2 + (int32_t)((lo_signed + 16384L) >> 15);
}

// v >> n (arithmetic, n in 0..31) with a whole-byte step first: a variable shift is a loop
// of single-bit steps on the AVR (and on the dsPIC for 32-bit values), a shift by 8 is a
// byte move. One out-of-line copy (noinline): inlined at its seven call sites it cost
// 0.15 kB of flash on the AVR proxy for a call's few cycles.
inline __attribute__((noinline)) int32_t asr32(int32_t v, uint8_t n) {
  if (n >= 8) {
    v >>= 8;
    n = (uint8_t)(n - 8);
    if (n >= 8) {
      v >>= 8;
      n = (uint8_t)(n - 8);
    }
  }
  return v >> n;
}

// round(v / 2^shift) for shift in 1..30 (ties up; arithmetic shift on every target).
inline int32_t round_shift(int32_t v, uint8_t shift) {
  return (int32_t)((v + ((int32_t)1 << (shift - 1))) >> shift);
}

// Clamps a 32-bit value into int16_t.
inline int16_t saturate_16(int32_t v) {
  if (v > 32767L) return 32767;
  if (v < -32768L) return -32768;
  return (int16_t)v;
}

// a + b clamped to the int32_t range (no signed overflow).
// (The limits are spelled out: avr-libc hides INT32_MAX from C++ without
// __STDC_LIMIT_MACROS.)
inline int32_t add_saturate_32(int32_t a, int32_t b) {
  const int32_t max = 2147483647L;
  const int32_t min = -max - 1;
  if (b > 0 && a > max - b) return max;
  if (b < 0 && a < min - b) return min;
  return a + b;
}

// |v| as unsigned (defined for INT32_MIN too).
inline uint32_t abs_u32(int32_t v) {
  return v < 0 ? (uint32_t)0 - (uint32_t)v : (uint32_t)v;
}

}  // namespace core

#endif  // FIRMWARE_CORE_FIXED_POINT_H
