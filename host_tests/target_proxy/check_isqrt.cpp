// On-target checks of core::isqrt32: floor(sqrt(n)) exact at k^2 - 1, k^2 and k^2 + 2k (the
// last n whose root is k) for a stride of k over the whole range, at the extremes, and on
// pseudo-random inputs of every magnitude.
#include "firmware/core/isqrt.h"

#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"

namespace proxy {

namespace {

const uint16_t kStride = 7;  // k = 1, 8, 15, ... plus 65535
const uint16_t kRandomInputs = 4096;

// True when r == floor(sqrt(n)): r^2 <= n < (r + 1)^2, written without overflow.
bool is_floor_sqrt(uint32_t n, uint16_t r) {
  const uint32_t square = (uint32_t)r * r;
  return square <= n && n - square <= 2UL * r;
}

// The three inputs around k^2 whose roots are known exactly.
void check_around_square(uint16_t k) {
  const uint32_t square = (uint32_t)k * k;
  PROXY_CHECK_EQ(core::isqrt32(square - 1), k - 1);
  PROXY_CHECK_EQ(core::isqrt32(square), k);
  PROXY_CHECK_EQ(core::isqrt32(square + 2UL * k), k);  // (k+1)^2 - 1, up to 2^32 - 1
}

}  // namespace

uint32_t next_random(uint32_t* state) {
  uint32_t x = *state;
  x ^= x << 13;
  x ^= x >> 17;
  x ^= x << 5;
  *state = x;
  return x;
}

void run_isqrt_checks() {
  begin_group(PROXY_STR("isqrt32"));
  PROXY_CHECK_EQ(core::isqrt32(0), 0);
  PROXY_CHECK_EQ(core::isqrt32(1), 1);
  PROXY_CHECK_EQ(core::isqrt32(2), 1);
  PROXY_CHECK_EQ(core::isqrt32(3), 1);
  PROXY_CHECK_EQ(core::isqrt32(0xFFFFFFFFUL), 65535U);
  for (uint32_t k = 1; k < 65535UL; k += kStride) check_around_square((uint16_t)k);
  check_around_square(65535U);
  uint32_t state = 0x12345678UL;
  for (uint16_t i = 0; i < kRandomInputs; ++i) {
    // Random magnitude too: shift by 0..31 so small inputs are as common as large ones.
    const uint32_t r = next_random(&state);
    const uint32_t n = r >> (i & 31U);
    PROXY_CHECK(is_floor_sqrt(n, core::isqrt32(n)));
  }
  end_group();
}

}  // namespace proxy
