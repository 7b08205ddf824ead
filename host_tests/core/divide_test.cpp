// 32/16 division, long division by 16 bits and the Newton reciprocal against 64-bit
// references: exact quotients, and the reciprocal's error bound over the whole range.
#include "firmware/core/divide.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

namespace {

TEST(Divide, Div32By16EqualsTheExactQuotientAndRemainder) {
  std::mt19937 rng(11);
  for (int i = 0; i < 300000; ++i) {
    uint16_t d = (uint16_t)rng();
    if (d == 0) d = 1;
    // n < d * 2^16, with the top of the range hit often.
    const uint32_t top = ((uint32_t)d << 16) - 1;
    const uint32_t n = (i % 4 == 0) ? top - (rng() % 8) : (uint32_t)(rng() % ((uint64_t)top + 1));
    uint16_t rem = 0;
    const uint16_t q = core::div_u32_u16(n, d, &rem);
    ASSERT_EQ(q, n / d) << n << " / " << d;
    ASSERT_EQ(rem, n % d) << n << " % " << d;
  }
  uint16_t rem = 0;
  EXPECT_EQ(core::div_u32_u16(0xFFFEFFFFUL, 65535, &rem), 65535U);  // the largest quotient
  EXPECT_EQ(rem, 65534U);
  EXPECT_EQ(core::div_u32_u16(0x7FFFFFFFUL, 32768, 0), 65535U);
  EXPECT_EQ(core::div_u32_u16(65535, 1, 0), 65535U);
}

// The shift-and-subtract loop the AVR proxy divides with (hosts use the hardware divider in
// div_u32_u16): full 16-step quotients and pre-aligned short ones.
TEST(Divide, ShiftSubtractLoopGivesQuotientAndRemainder) {
  std::mt19937 rng(16);
  for (int i = 0; i < 300000; ++i) {
    uint16_t d = (uint16_t)rng();
    if (d == 0) d = 1;
    const uint32_t top = ((uint32_t)d << 16) - 1;
    const uint32_t n = (i % 4 == 0) ? top : (uint32_t)(rng() % ((uint64_t)top + 1));
    const uint32_t acc = core::shift_subtract_divide(n, d, 16);
    ASSERT_EQ((uint16_t)acc, n / d) << n << " / " << d;
    ASSERT_EQ(acc >> 16, n % d) << n << " % " << d;
    const uint8_t bits = (uint8_t)(1 + rng() % 16);
    const uint32_t m = (uint32_t)(rng() % (((uint64_t)d << bits)));  // quotient < 2^bits
    ASSERT_EQ((uint16_t)core::shift_subtract_divide(m << (16 - bits), d, bits), m / d)
        << m << " / " << d << ", " << +bits;
  }
}

TEST(Divide, LongDivisionBy16BitsIsExactForEveryNumerator) {
  std::mt19937 rng(12);
  for (int i = 0; i < 300000; ++i) {
    const uint32_t n = rng();
    uint16_t d = (uint16_t)(rng() >> (rng() % 16));
    if (d == 0) d = 1;
    uint16_t rem = 0;
    ASSERT_EQ(core::div_u32_by_u16(n, d, &rem), n / d) << n << " / " << d;
    ASSERT_EQ(rem, n % d);
  }
  EXPECT_EQ(core::div_u32_by_u16(0xFFFFFFFFUL, 1, 0), 0xFFFFFFFFUL);
  EXPECT_EQ(core::div_u32_by_u16(123, 0, 0), 0xFFFFFFFFUL);  // documented, not a trap
}

// Exact 1/w in the reciprocal's scale, as a double.
double exact_r_q62(int32_t w, uint8_t shift) {
  return std::ldexp(1.0, 62) / std::ldexp((double)w, shift);
}

TEST(Divide, ReciprocalIsWithin2ToTheMinus27OverTheWholeRange) {
  std::mt19937 rng(13);
  double worst = 0;
  auto check = [&](int32_t w) {
    const core::Reciprocal r = core::reciprocal_of(w);
    const double wn = std::ldexp((double)w, r.shift);
    ASSERT_GE(wn, std::ldexp(1.0, 30)) << w;
    ASSERT_LT(wn, std::ldexp(1.0, 31)) << w;
    const double rel = std::fabs(r.r_q62 / exact_r_q62(w, r.shift) - 1);
    worst = std::max(worst, rel);
  };
  for (int k = 0; k < 31; ++k) {  // every power of two and its neighbours
    const int64_t p = (int64_t)1 << k;
    for (int64_t w = p - 3; w <= p + 3; ++w)
      if (w >= 1 && w <= INT32_MAX) check((int32_t)w);
  }
  for (int i = 0; i < 500000; ++i) check((int32_t)(rng() >> (1 + rng() % 31)) | 1);
  EXPECT_LT(worst, std::ldexp(1.0, -27));
  // Non-positive w is treated as 1, never a division by zero.
  EXPECT_EQ(core::reciprocal_of(0).r_q62, core::reciprocal_of(1).r_q62);
  EXPECT_EQ(core::reciprocal_of(-5).shift, core::reciprocal_of(1).shift);
}

TEST(Divide, MulReciprocalQ27IsTheRoundedQuotientWithinItsBound) {
  std::mt19937 rng(14);
  for (int i = 0; i < 400000; ++i) {
    // w in Q27 up to 2^28 (weights normalised to <= 1, with room), down to tiny weights.
    const int32_t w = (int32_t)(1 + rng() % (1U << 28)) >> (rng() % 20);
    const int32_t wpos = w < 1 ? 1 : w;
    // A quotient below 2^29 in magnitude, and the numerator that gives it.
    const int64_t q_want = (int64_t)(rng() % (1U << 29)) * ((rng() & 1) ? 1 : -1);
    const int32_t x = (int32_t)std::llround((double)q_want * wpos / (double)(1 << 27));
    const double exact = (double)x * (double)(1 << 27) / wpos;
    if (std::fabs(exact) >= std::ldexp(1.0, 29)) continue;
    const int32_t got = core::mul_reciprocal_q27(x, core::reciprocal_of(wpos));
    ASSERT_LE(std::fabs(got - exact), 1.0 + std::fabs(exact) * std::ldexp(1.0, -27))
        << x << " / " << wpos;
  }
}

TEST(Divide, MulReciprocalQ27ClampsInsteadOfOverflowing) {
  const core::Reciprocal tiny = core::reciprocal_of(1);  // 1/w = 2^27 in Q27
  // x * 2^27 would need 58 bits: the result is clamped near 2^30 with the right sign.
  EXPECT_NEAR(core::mul_reciprocal_q27(INT32_MAX, tiny), 1L << 30, 2);
  EXPECT_NEAR(core::mul_reciprocal_q27(INT32_MIN, tiny), -(1L << 30), 2);
  EXPECT_EQ(core::mul_reciprocal_q27(0, tiny), 0);
}

}  // namespace
