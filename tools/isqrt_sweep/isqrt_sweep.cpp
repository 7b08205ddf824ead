// Exhaustive sweep of core::isqrt32: every uint32 input against the expected floor root.
// Usage: isqrt_sweep [first [last]]   (defaults 0 and 4294967295; decimal or 0x hex)
// Exit status: 0 all exact, 1 a mismatch (the first ones are printed), 2 bad arguments.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "firmware/core/isqrt.h"

namespace {

// Parses a 32-bit unsigned argument; false on junk or overflow.
bool parse_u32(const char* s, uint32_t* out) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(s, &end, 0);
  if (end == s || *end != '\0' || v > 0xFFFFFFFFull) return false;
  *out = (uint32_t)v;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t first = 0, last = 0xFFFFFFFFu;
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::printf("usage: isqrt_sweep [first [last]]\nexample: isqrt_sweep 0 0xFFFF\n");
    return 0;
  }
  if ((argc > 1 && !parse_u32(argv[1], &first)) || (argc > 2 && !parse_u32(argv[2], &last)) ||
      argc > 3 || first > last) {
    std::fprintf(stderr, "isqrt_sweep: bad range (usage: isqrt_sweep [first [last]])\n");
    return 2;
  }
  const auto t0 = std::chrono::steady_clock::now();
  // The expected root walks up with n: root r holds for r^2 <= n < (r+1)^2.
  uint64_t root = 0;
  while ((root + 1) * (root + 1) <= first) ++root;
  uint64_t next_square = (root + 1) * (root + 1);
  uint64_t mismatches = 0;
  uint64_t n = first;
  for (;; ++n) {
    if (n == next_square) {
      ++root;
      next_square = (root + 1) * (root + 1);
    }
    const uint16_t got = core::isqrt32((uint32_t)n);
    if (got != root) {
      if (mismatches < 10) {
        std::printf("mismatch: isqrt32(%llu) = %u, expected %llu\n", (unsigned long long)n, got,
                    (unsigned long long)root);
      }
      ++mismatches;
    }
    if (n == last) break;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("isqrt32 sweep %u..%u: %llu inputs, %llu mismatches, %.1f s\n", first, last,
              (unsigned long long)(n - first + 1), (unsigned long long)mismatches, seconds);
  return mismatches == 0 ? 0 : 1;
}
