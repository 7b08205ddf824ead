// Planted violation: constexpr variable and function.
#include <stdint.h>  // int32_t

constexpr int32_t kLimit = 5;  // expect: constexpr
static constexpr int32_t twice(int32_t v) { return 2 * v; }  // expect: constexpr

int32_t use_limit() { return twice(kLimit); }
