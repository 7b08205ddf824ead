// Test-only stand-in for the TMC428 in velocity mode: per-axis v_actual ramps toward
// v_target at a_max (native units per ms), positions integrate the velocity in 0.1 ms
// sub-steps, limit switches sit at configured positions. Records the path for error checks.
#ifndef HOST_TESTS_APP_KINEMATIC_PLANT_H
#define HOST_TESTS_APP_KINEMATIC_PLANT_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "firmware/config/machine_config.h"
#include "hal/interfaces/motion_axes.h"

namespace fake_app {

struct PlantAxis {
  uint32_t usteps_per_s_per_unit_q16 = 2500000;  // 10 MHz, pulse_div 2: 38.15 usteps/s
  int16_t max_units = 2047;
  uint16_t accel_units_per_ms = 13;  // ~194 mm/s^2 at 2560 usteps/mm
  double limit_left_usteps = -1e12;  // switch active at or below
  double limit_right_usteps = 1e12;  // switch active at or above
};

class KinematicPlant : public hal::MotionAxes {
 public:
  static constexpr int kSubSteps = 10;
  std::array<PlantAxis, 3> axis;
  std::array<double, 3> pos_usteps{};  // exact position
  std::array<double, 3> v_actual{};    // native units (fractional, like the chip's 8 bits)
  std::array<int16_t, 3> v_target{};
  bool record = false;
  std::vector<std::array<double, 3>> path;  // positions every sub-step while recording
  int writes = 0;
  int position_writes = 0;
  bool fail_reads = false;

  KinematicPlant() {
    axis[2].accel_units_per_ms = 3;  // Z: ~49 mm/s^2
  }

  // Advances the plant by one millisecond.
  void step_1ms() {
    for (int s = 0; s < kSubSteps; ++s) {
      for (int i = 0; i < 3; ++i) {
        const double dv = axis[i].accel_units_per_ms / double(kSubSteps);
        double v = v_actual[i];
        const double goal = v_target[i];
        if (v < goal)
          v = std::min(goal, v + dv);
        else if (v > goal)
          v = std::max(goal, v - dv);
        const double mean = 0.5 * (v + v_actual[i]);
        v_actual[i] = v;
        pos_usteps[i] += mean * axis[i].usteps_per_s_per_unit_q16 / 65536.0 / 1000.0 / kSubSteps;
      }
      if (record) path.push_back(pos_usteps);
    }
  }

  uint8_t limits() const {
    uint8_t bits = 0;
    for (int i = 0; i < 3; ++i) {
      if (pos_usteps[i] <= axis[i].limit_left_usteps) bits |= uint8_t(1u << (2 * i));
      if (pos_usteps[i] >= axis[i].limit_right_usteps) bits |= uint8_t(2u << (2 * i));
    }
    return bits;
  }

  bool read_actual_usteps(int32_t out[config::kAxisCount]) override {
    if (fail_reads) return false;
    for (int i = 0; i < 3; ++i) out[i] = int32_t(std::floor(pos_usteps[i]));
    return true;
  }
  bool write_velocity_units(const int16_t v[config::kAxisCount]) override {
    ++writes;
    for (int i = 0; i < 3; ++i) {
      int16_t c = v[i];
      if (c > axis[i].max_units) c = axis[i].max_units;
      if (c < -axis[i].max_units) c = int16_t(-axis[i].max_units);
      v_target[i] = c;
    }
    return true;
  }
  bool read_velocity_units(int16_t out[config::kAxisCount]) override {
    for (int i = 0; i < 3; ++i) out[i] = int16_t(v_actual[i]);
    return true;
  }
  bool set_actual_usteps(const int32_t usteps[config::kAxisCount]) override {
    ++position_writes;
    for (int i = 0; i < 3; ++i) pos_usteps[i] = usteps[i];
    return true;
  }
  bool read_limits(uint8_t* bits) override {
    *bits = limits();
    return true;
  }
  uint32_t usteps_per_s_per_unit_q16(uint8_t a) const override {
    return axis[a].usteps_per_s_per_unit_q16;
  }
  int16_t max_velocity_units(uint8_t a) const override { return axis[a].max_units; }
  uint16_t accel_units_per_ms(uint8_t a) const override { return axis[a].accel_units_per_ms; }

  bool moving() const { return v_actual[0] != 0 || v_actual[1] != 0 || v_actual[2] != 0; }
};

}  // namespace fake_app

#endif  // HOST_TESTS_APP_KINEMATIC_PLANT_H
