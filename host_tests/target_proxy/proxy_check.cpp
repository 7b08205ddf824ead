// Counting and reporting of the target-proxy checks.
#include "host_tests/target_proxy/proxy_check.h"

namespace proxy {

namespace {

const uint8_t kMaxPrintedFailures = 24;  // keep a broken run's output readable
uint32_t g_passed;
uint32_t g_failed;
uint32_t g_group_passed;
uint32_t g_group_failed;
const char* g_group;  // flash text, set by begin_group

// Prints the start of a failure line; false when too many were printed already.
bool fail_header(const char* expr, uint16_t line) {
  ++g_failed;
  ++g_group_failed;
  if (g_failed > kMaxPrintedFailures) return false;
  PROXY_PRINTF("FAIL ");
  PROXY_PRINT_STR(g_group);
  PROXY_PRINTF(" line %u: ", (unsigned)line);
  PROXY_PRINT_STR(expr);
  return true;
}

void pass() {
  ++g_passed;
  ++g_group_passed;
}

}  // namespace

void begin_group(const char* name) {
  g_group = name;
  g_group_passed = 0;
  g_group_failed = 0;
}

void end_group() {
  PROXY_PRINTF("group ");
  PROXY_PRINT_STR(g_group);
  PROXY_PRINTF(": %lu passed, %lu failed\n", (unsigned long)g_group_passed,
               (unsigned long)g_group_failed);
}

bool check(bool ok, const char* expr, uint16_t line) {
  if (ok) {
    pass();
  } else if (fail_header(expr, line)) {
    PROXY_PRINTF("\n");
  }
  return ok;
}

bool check_eq(int32_t got, int32_t want, const char* expr, uint16_t line) {
  if (got == want) {
    pass();
    return true;
  }
  if (fail_header(expr, line)) {
    PROXY_PRINTF(" (got %ld, want %ld)\n", (long)got, (long)want);
  }
  return false;
}

bool check_near(int32_t got, int32_t want, int32_t tolerance, const char* expr, uint16_t line) {
  const int32_t diff = got > want ? got - want : want - got;
  if (diff <= tolerance && diff >= 0) {
    pass();
    return true;
  }
  if (fail_header(expr, line)) {
    PROXY_PRINTF(" (got %ld, want %ld, tolerance %ld)\n", (long)got, (long)want, (long)tolerance);
  }
  return false;
}

uint32_t passed_count() {
  return g_passed;
}

uint32_t failed_count() {
  return g_failed;
}

void print_summary() {
  PROXY_PRINTF("%lu passed, %lu failed\n", (unsigned long)g_passed, (unsigned long)g_failed);
}

}  // namespace proxy
