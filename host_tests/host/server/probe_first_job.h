// A probe-first board job on a tilted blank, for the tests of the operator's controls while
// the server probes (hold, resume, abort at any instant of a touch).
#ifndef HOST_TESTS_HOST_SERVER_PROBE_FIRST_JOB_H
#define HOST_TESTS_HOST_SERVER_PROBE_FIRST_JOB_H

#include <cmath>    // std::lround
#include <cstddef>  // size_t
#include <cstdint>  // int32_t, int64_t
#include <string>   // std::string

#include "host_tests/host/server/blinky_upload.h"  // blinky, post
#include "host_tests/host/server/server_test_rig.h"

namespace host::server::test {

// The blinky board probed first on a grid `spacing_mm` apart: the new job's id.
inline int64_t post_probe_first(const ServerRig& server, const std::string& spacing_mm) {
  return post(server, blinky({{"probe_first", "1"}, {"probe_spacing_mm", spacing_mm}}));
}

// A blank tilted 0.1 mm over 50 mm in x (um above the zero corner's copper).
inline int32_t tilted_um(int32_t x_um, int32_t) {
  return static_cast<int32_t>(std::lround(2.0 * x_um / 1000.0));
}

// The tilted copper's height at x, mm.
inline double tilted_copper_mm(double x_mm) {
  return tilted_um(static_cast<int32_t>(std::lround(x_mm * 1000)), 0) / 1000.0;
}

inline sim::SimOptions tilted_blank() {
  sim::SimOptions o;
  o.surface_um = tilted_um;
  return o;
}

// The touches the running job `id` has made, 0 before it probes.
inline size_t touches(const ServerRig& server, int64_t id) {
  const nlohmann::json j = server.running(id);
  return j.is_object() && j.contains("probe") ? j["probe"]["touches"].get<size_t>() : 0;
}

}  // namespace host::server::test

#endif  // HOST_TESTS_HOST_SERVER_PROBE_FIRST_JOB_H
