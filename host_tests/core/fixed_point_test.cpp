// Fixed-point helpers: exact widening products, rounding and saturation at the range ends.
#include "firmware/core/fixed_point.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

namespace {

TEST(FixedPoint, Mul32x16Uq16EqualsFloorOfTheWideProduct) {
  std::mt19937 rng(7);
  for (int i = 0; i < 200000; ++i) {
    const int32_t a = (int32_t)rng();
    const uint16_t b = (uint16_t)rng();
    const int64_t wide = (int64_t)a * b;
    const int64_t expected = wide >= 0 ? wide / 65536 : -((-wide + 65535) / 65536);
    ASSERT_EQ(core::mul_32x16_uq16(a, b), expected) << a << " * " << b;
  }
}

TEST(FixedPoint, Mul32x16Uq16AtTheExtremes) {
  EXPECT_EQ(core::mul_32x16_uq16(INT32_MIN, 65535), -2147450880);  // -2^31 * (1 - 2^-16)
  EXPECT_EQ(core::mul_32x16_uq16(INT32_MAX, 65535), 2147450879);
  EXPECT_EQ(core::mul_32x16_uq16(-1, 1), -1);  // floor(-2^-16)
  EXPECT_EQ(core::mul_32x16_uq16(12345, 0), 0);
}

TEST(FixedPoint, Mul32x16Q15RoundsTheWideProduct) {
  std::mt19937 rng(8);
  for (int i = 0; i < 200000; ++i) {
    const int32_t a = (int32_t)rng() >> 2;  // keep |a * b / 2^15| < 2^31
    const int16_t b = (int16_t)rng();
    const int64_t wide = (int64_t)a * b;
    const int64_t expected = (int64_t)std::floor((double)wide / 32768.0 + 0.5);
    ASSERT_EQ(core::mul_32x16_q15(a, b), expected) << a << " * " << b;
  }
}

TEST(FixedPoint, RoundShiftRoundsHalfUp) {
  EXPECT_EQ(core::round_shift(96, 6), 2);    // 1.5 -> 2
  EXPECT_EQ(core::round_shift(95, 6), 1);    // 1.48 -> 1
  EXPECT_EQ(core::round_shift(-96, 6), -1);  // -1.5 -> -1
  EXPECT_EQ(core::round_shift(-97, 6), -2);
}

TEST(FixedPoint, SaturationClampsAtBothEnds) {
  EXPECT_EQ(core::saturate_16(40000), 32767);
  EXPECT_EQ(core::saturate_16(-40000), -32768);
  EXPECT_EQ(core::saturate_16(-5), -5);
  EXPECT_EQ(core::add_saturate_32(INT32_MAX, 1), INT32_MAX);
  EXPECT_EQ(core::add_saturate_32(INT32_MIN, -1), INT32_MIN);
  EXPECT_EQ(core::add_saturate_32(-7, 3), -4);
  EXPECT_EQ(core::abs_u32(INT32_MIN), 2147483648u);
}

}  // namespace
