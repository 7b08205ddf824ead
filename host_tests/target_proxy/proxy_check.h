// A tiny assertion harness for the target proxy (GoogleTest cannot run on an 8 KB AVR):
// checks are counted per group, failures print group, line, expression and values, and the
// run ends with "N passed, N failed".
#ifndef HOST_TESTS_TARGET_PROXY_PROXY_CHECK_H
#define HOST_TESTS_TARGET_PROXY_PROXY_CHECK_H

#include <stdint.h>  // int32_t, uint32_t

#include "host_tests/target_proxy/proxy_platform.h"  // PROXY_STR

namespace proxy {

// Starts a named group of checks (name is flash text: PROXY_STR("...")).
void begin_group(const char* name);
// Prints the group's pass/fail counts.
void end_group();

// Records one check; on failure prints where and what.
bool check(bool ok, const char* expr, uint16_t line);
// Records got == want; on failure prints both.
bool check_eq(int32_t got, int32_t want, const char* expr, uint16_t line);
// Records |got - want| <= tolerance; on failure prints both and the tolerance.
bool check_near(int32_t got, int32_t want, int32_t tolerance, const char* expr, uint16_t line);

uint32_t passed_count();
uint32_t failed_count();
// Prints the final "N passed, N failed" line.
void print_summary();

}  // namespace proxy

#define PROXY_CHECK(cond) ::proxy::check((cond), PROXY_STR(#cond), __LINE__)
#define PROXY_CHECK_EQ(got, want) \
  ::proxy::check_eq((int32_t)(got), (int32_t)(want), PROXY_STR(#got " == " #want), __LINE__)
#define PROXY_CHECK_NEAR(got, want, tol)                               \
  ::proxy::check_near((int32_t)(got), (int32_t)(want), (int32_t)(tol), \
                      PROXY_STR("|" #got " - " #want "| <= " #tol), __LINE__)

#endif  // HOST_TESTS_TARGET_PROXY_PROXY_CHECK_H
