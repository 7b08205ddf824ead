// Wide products from 16x16 products against 64-bit (and 128-bit) references: exact
// products, sums, leading bits and slices; the q30 product within its stated error.
#include "firmware/core/wide_product.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

namespace {

int64_t as_int64(const core::Wide& w) {
  return (int64_t)(((uint64_t)w.hi << 32) | w.lo);
}

int32_t random_int32(std::mt19937& rng) {
  const int bits = (int)(rng() % 32);  // every magnitude, not only the huge ones
  const int32_t v = (int32_t)(rng() & ((bits == 31 ? 0x7FFFFFFFU : (1U << bits) - 1)));
  return (rng() & 1) ? -v : v;
}

TEST(WideProduct, MulWideIsTheExact64BitProduct) {
  std::mt19937 rng(31);
  for (int i = 0; i < 300000; ++i) {
    const int32_t a = random_int32(rng);
    const int32_t b = random_int32(rng);
    ASSERT_EQ(as_int64(core::mul_wide(a, b)), (int64_t)a * b) << a << " * " << b;
  }
  const int32_t min = INT32_MIN;
  EXPECT_EQ(as_int64(core::mul_wide(min, min)), (int64_t)min * min);
  EXPECT_EQ(as_int64(core::mul_wide(min, INT32_MAX)), (int64_t)min * INT32_MAX);
}

TEST(WideProduct, SumsDifferencesSignsAndMagnitudesAreExact) {
  std::mt19937 rng(32);
  for (int i = 0; i < 200000; ++i) {
    const int64_t x = (int64_t)random_int32(rng) * random_int32(rng);
    const int64_t y = (int64_t)random_int32(rng) * random_int32(rng);
    core::Wide a;
    a.hi = (uint32_t)((uint64_t)x >> 32);
    a.lo = (uint32_t)x;
    core::Wide b;
    b.hi = (uint32_t)((uint64_t)y >> 32);
    b.lo = (uint32_t)y;
    ASSERT_EQ(as_int64(core::wide_add(a, b)), x + y);
    ASSERT_EQ(as_int64(core::wide_sub(a, b)), x - y);
    ASSERT_EQ(core::wide_negative(a), x < 0);
    const int64_t ax = x < 0 ? -x : x;
    ASSERT_EQ(as_int64(core::wide_abs(a)), ax);
    int bits = 0;
    while (bits < 64 && ((uint64_t)ax >> bits) != 0) ++bits;
    ASSERT_EQ(core::wide_bit_length(core::wide_abs(a)), bits) << ax;
    const uint8_t shift = (uint8_t)(rng() % 64);
    ASSERT_EQ(core::wide_shift_right_low(core::wide_abs(a), shift),
              (uint32_t)((uint64_t)ax >> shift))
        << ax << " >> " << (int)shift;
  }
}

TEST(WideProduct, MulQ30IsTheFlooredProductOrOneLess) {
  std::mt19937 rng(33);
  for (int i = 0; i < 300000; ++i) {
    const int32_t a = random_int32(rng) >> 1;  // |a|, |b| < 2^30
    const int32_t b = random_int32(rng) >> 1;
    const int64_t p = (int64_t)a * b;
    const int64_t floor_q30 = p >= 0 ? p >> 30 : -((-p + (1LL << 30) - 1) >> 30);
    const int32_t got = core::mul_q30(a, b);
    ASSERT_TRUE(got == floor_q30 || got == floor_q30 - 1)
        << a << " * " << b << " = " << got << ", floor " << floor_q30;
  }
}

}  // namespace
