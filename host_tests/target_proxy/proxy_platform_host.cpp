// The proxy platform on the host: stdout and a nanosecond clock (for a quick native run of
// the same checks; its timings say nothing about the target).
#include <stdlib.h>  // exit
#include <time.h>    // clock_gettime

#include "host_tests/target_proxy/proxy_platform.h"

namespace proxy {

void platform_init() {
  setvbuf(stdout, 0, _IOLBF, 0);
}

uint32_t cycles_now() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (uint32_t)((uint64_t)ts.tv_sec * 1000000000ULL + (uint64_t)ts.tv_nsec);
}

uint32_t cycles_overhead() {
  return 0;
}

uint32_t counter_hz() {
  return 1000000000UL;
}

const char* counter_unit() {
  return "ns";
}

uint16_t stack_peak_bytes() {
  return 0;
}

uint16_t static_ram_bytes() {
  return 0;
}

void platform_finish(bool all_passed) {
  fflush(stdout);
  exit(all_passed ? 0 : 1);
}

}  // namespace proxy
