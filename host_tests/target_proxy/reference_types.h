// Records of the generated reference tables (reference_data.h, written on the host by
// make_reference from Eigen's double-precision B-splines) that the proxy runner checks.
#ifndef HOST_TESTS_TARGET_PROXY_REFERENCE_TYPES_H
#define HOST_TESTS_TARGET_PROXY_REFERENCE_TYPES_H

#include <stdint.h>  // int32_t, uint32_t

#include "firmware/core/spline.h"  // PointUm

namespace proxy {

// A curve point: curve index, knot span, parameter inside the span (0..65536), and the
// double-precision point rounded to 1/64 um (the evaluator's q6 format).
struct PointRef {
  uint8_t curve;
  uint16_t span;
  uint32_t t_q16;
  int32_t x_q6;
  int32_t y_q6;
};

// A stepping run: settings, the curve ends from the double reference (offset 0 runs), and
// the count/hash of the points the host build of the same walker emitted.
struct StepRef {
  uint8_t curve;
  uint8_t mode;   // core::StepMode
  uint8_t error;  // core::GeometryError after the last point
  uint16_t chord_tolerance_um;
  int32_t tool_offset_um;
  uint16_t count;
  uint32_t hash;
  core::PointUm first;  // offset 0: the curve start (Eigen), else the host's first point
  core::PointUm last;   // offset 0: the curve end (Eigen), else the host's last point
};

// FNV-1a over a point's coordinates, low byte first (the same on every platform).
inline uint32_t hash_point(uint32_t hash, const core::PointUm& p) {
  const uint32_t words[2] = {(uint32_t)p.x_um, (uint32_t)p.y_um};
  for (uint8_t w = 0; w < 2; ++w) {
    for (uint8_t b = 0; b < 4; ++b) {
      hash ^= (uint8_t)(words[w] >> (8 * b));
      hash *= 16777619UL;
    }
  }
  return hash;
}

static const uint32_t kHashSeed = 2166136261UL;
// Upper bound on points of one stepping run (a runaway walker fails instead of hanging).
static const uint16_t kMaxStepPoints = 20000;

}  // namespace proxy

#endif  // HOST_TESTS_TARGET_PROXY_REFERENCE_TYPES_H
