// The groups of on-target checks and measurements the proxy runner executes in order.
#ifndef HOST_TESTS_TARGET_PROXY_PROXY_CHECKS_H
#define HOST_TESTS_TARGET_PROXY_PROXY_CHECKS_H

#include <stdint.h>  // uint8_t, uint32_t

#include "firmware/core/spline.h"  // Spline

namespace proxy {

// core::isqrt32 exact around perfect squares and on pseudo-random inputs.
void run_isqrt_checks();
// core::SpscRing order, capacity, 16-bit index wrap-around, peek.
void run_ring_checks();
// Fixed-point De Boor points against double-precision (Eigen) reference points.
void run_deboor_checks();
// Parameter stepping: curve ends against Eigen, point sequences against the host build.
void run_curve_walker_checks();
// Cycle counts of the per-point and per-tick work, and memory figures.
void run_measurements();
// Path-controller tick and planner push on a small plant model (when fw_app is built).
void run_app_measurements();

// Reference curve `index` (a RAM copy of the generated flash table; one at a time), and
// how many there are (0 when built without reference data).
const core::Spline& reference_curve(uint8_t index);
uint8_t reference_curve_count();
// The same RAM as a scratch spline (RAM is 8 KB: one Spline copy is 918 bytes).
core::Spline* scratch_spline();

// xorshift32: the pseudo-random inputs (same sequence on every platform).
uint32_t next_random(uint32_t* state);

}  // namespace proxy

#endif  // HOST_TESTS_TARGET_PROXY_PROXY_CHECKS_H
