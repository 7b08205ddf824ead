// The target-proxy runner: the core's essential checks and cycle measurements, run on an
// ATmega2560 in simavr (16-bit int, 32-bit double, 8 KB RAM, no C++ library) by ctest, or
// natively on the host. Ends with "N passed, N failed".
#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"
#include "host_tests/target_proxy/proxy_platform.h"

int main() {
  proxy::platform_init();
  PROXY_PRINTF("engraver target proxy: sizeof(int) %u, sizeof(double) %u, counter %lu Hz\n",
               (unsigned)sizeof(int), (unsigned)sizeof(double), (unsigned long)proxy::counter_hz());
  proxy::run_isqrt_checks();
  proxy::run_ring_checks();
  proxy::run_deboor_checks();
  proxy::run_curve_walker_checks();
  proxy::run_measurements();
  proxy::run_app_measurements();
  PROXY_PRINTF("memory static RAM %u bytes, stack peak %u bytes\n",
               (unsigned)proxy::static_ram_bytes(), (unsigned)proxy::stack_peak_bytes());
  proxy::print_summary();
  proxy::platform_finish(proxy::failed_count() == 0);
  return 0;
}
