// Unit conversions between micrometres, TMC428 microsteps and the chip's native velocity
// units, computed once at start-up so the 1 ms tick uses only 16x16 and 32x16 products.
#ifndef FIRMWARE_APP_AXIS_SCALING_H
#define FIRMWARE_APP_AXIS_SCALING_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/config/machine_config.h"  // MachineConfig, kAxisCount
#include "hal/interfaces/motion_axes.h"      // MotionAxes (chip units)

namespace app {

struct AxisScaling {
  int32_t usteps_per_mm[config::kAxisCount];    // um -> usteps when a target is taken
  uint16_t um_per_ustep_q[config::kAxisCount];  // Q(um_shift): usteps -> um
  uint8_t um_shift;
  uint16_t units_per_um_s_q[config::kAxisCount];  // Q(units_shift): um/s -> native units
  uint8_t units_shift;
  int16_t max_units[config::kAxisCount];                // chip v_max
  uint16_t max_speed_um_s[config::kAxisCount];          // min(config rapid limit, chip v_max)
  uint16_t chip_accel_um_s_per_ms[config::kAxisCount];  // what the chip's ramp does
  uint16_t plan_accel_um_s_per_ms[config::kAxisCount];  // what the planner assumes (< chip)
  int32_t travel_um[config::kAxisCount];                // work area: 0..travel
};

// The planner uses this fraction (in 1/256) of the chip's ramp so the chip always keeps up.
static const uint16_t kPlanAccelFraction256 = 192;

// Fills s from the machine description and what the motion chip reports. Returns false
// (and a safe, slow scaling) when a value is outside what the fixed-point paths support.
bool build_axis_scaling(const config::MachineConfig& cfg, const hal::MotionAxes& motion,
                        AxisScaling* s);

// Micrometres to microsteps on one axis: trunc(um * usteps_per_mm / 1000), exact while the
// result fits 31 bits. 32/16 divisions only (usteps_per_mm < 2^16, see build_axis_scaling).
int32_t um_to_usteps(const AxisScaling& s, uint8_t axis, int32_t um);

// Microsteps to micrometres (rounded toward minus infinity).
int32_t usteps_to_um(const AxisScaling& s, uint8_t axis, int32_t usteps);

}  // namespace app

#endif  // FIRMWARE_APP_AXIS_SCALING_H
