// isqrt32: exact floor(sqrt(n)) at every perfect square and its neighbours, and at random n.
#include "firmware/core/isqrt.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

namespace {

// floor(sqrt(n)) by definition: r*r <= n < (r+1)^2, checked in 64-bit.
bool is_floor_sqrt(uint32_t n, uint32_t r) {
  const uint64_t r64 = r;
  return r64 * r64 <= n && (r64 + 1) * (r64 + 1) > n;
}

TEST(Isqrt, ExactAtEverySquareAndItsNeighboursUpTo65535) {
  for (uint32_t k = 0; k <= 65535; ++k) {
    const uint32_t sq = k * k;
    ASSERT_EQ(core::isqrt32(sq), k) << "k*k, k=" << k;
    if (k > 0) ASSERT_EQ(core::isqrt32(sq - 1), k - 1) << "k*k-1, k=" << k;
    ASSERT_EQ(core::isqrt32(sq + 2 * k), k) << "k*k+2k, k=" << k;  // last n with root k
  }
}

TEST(Isqrt, ExtremesOfTheInputRange) {
  EXPECT_EQ(core::isqrt32(0), 0u);
  EXPECT_EQ(core::isqrt32(1), 1u);
  EXPECT_EQ(core::isqrt32(2), 1u);
  EXPECT_EQ(core::isqrt32(3), 1u);
  EXPECT_EQ(core::isqrt32(4), 2u);
  EXPECT_EQ(core::isqrt32(0xFFFFFFFFu), 65535u);
  EXPECT_EQ(core::isqrt32(0xFFFE0001u), 65535u);  // 65535^2
  EXPECT_EQ(core::isqrt32(0xFFFE0000u), 65534u);
}

TEST(Isqrt, MatchesTheDefinitionOnAMillionRandomInputs) {
  std::mt19937 rng(12345);
  for (int i = 0; i < 1000000; ++i) {
    const uint32_t n = rng();
    ASSERT_TRUE(is_floor_sqrt(n, core::isqrt32(n))) << "n=" << n;
  }
}

}  // namespace
