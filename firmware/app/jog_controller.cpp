// Manual zeroing with the joystick (see jog_controller.h).
#include "firmware/app/jog_controller.h"

#include <string.h>  // memcpy, memset

#include "hal/interfaces/motion_axes.h"      // LimitBits
#include "hal/interfaces/operator_inputs.h"  // InputBits

namespace app {

// Every member starts at zero (phase_ kJogging): one memset, less code than a store each
// (no virtuals).
JogController::JogController() {
  memset(static_cast<void*>(this), 0, sizeof *this);
}

void JogController::init(const AxisScaling& scaling) {
  scaling_ = scaling;
}

void JogController::start(uint8_t axes_mask, uint8_t inputs) {
  axes_mask_ = axes_mask;
  prev_inputs_ = inputs;
  speed_um_s_ = 0;
  phase_ = kJogging;
  still_ticks_ = 0;
  z_mode_ = false;
}

// Velocity of one axis at the current jog speed, unless that runs into an active limit.
void JogController::set_velocity(uint8_t axis, int8_t sign, uint8_t limits,
                                 int16_t v_units[3]) const {
  const uint8_t toward = (uint8_t)((sign < 0 ? 1U : 2U) << (2 * axis));  // left / right bit
  if (limits & toward) return;
  uint16_t speed = speed_um_s_;
  if (speed > scaling_.max_speed_um_s[axis]) speed = scaling_.max_speed_um_s[axis];
  int32_t units = ((int32_t)speed * scaling_.units_per_um_s_q[axis]) >> scaling_.units_shift;
  if (units < 1) units = 1;
  if (units > scaling_.max_units[axis]) units = scaling_.max_units[axis];
  v_units[axis] = (int16_t)(sign < 0 ? -units : units);
}

JogResult JogController::tick(uint8_t inputs, uint8_t limits,
                              const int32_t pos_usteps[config::kAxisCount],
                              int16_t v_units[config::kAxisCount]) {
  memset(v_units, 0, config::kAxisCount * sizeof v_units[0]);
  const uint8_t pressed = (uint8_t)(inputs & ~prev_inputs_);
  prev_inputs_ = inputs;
  if (phase_ == kSettling) {
    // Wait until the chip's ramp has brought every axis to a standstill.
    bool still = true;
    for (uint8_t i = 0; i < config::kAxisCount; ++i) {
      if (pos_usteps[i] != last_pos_[i]) still = false;
      last_pos_[i] = pos_usteps[i];
    }
    still_ticks_ = still ? (uint8_t)(still_ticks_ + 1) : 0;
    if (still_ticks_ < kJogSettleTicks) return JogResult::kRunning;
    if (!confirm_) return JogResult::kCancelled;
    for (uint8_t i = 0; i < config::kAxisCount; ++i) {
      zero_usteps_[i] = (axes_mask_ & (1U << i)) ? 0 : pos_usteps[i];
    }
    return JogResult::kConfirmed;
  }
  if (pressed & (hal::kButtonConfirm | hal::kButtonClear)) {
    confirm_ = (pressed & hal::kButtonClear) == 0;
    phase_ = kSettling;
    still_ticks_ = 0;
    memcpy(last_pos_, pos_usteps, sizeof last_pos_);
    return JogResult::kRunning;
  }
  if (pressed & hal::kButtonZ) z_mode_ = !z_mode_;
  const uint8_t dirs =
      (uint8_t)(inputs & (hal::kJoyLeft | hal::kJoyRight | hal::kJoyDown | hal::kJoyUp));
  if (dirs == 0) {
    speed_um_s_ = 0;  // released: the chip ramps down at a_max
    return JogResult::kRunning;
  }
  // Held: start slow for fine positioning, then speed up for long moves.
  if (speed_um_s_ < kJogStartUmS) {
    speed_um_s_ = kJogStartUmS;
  } else if (speed_um_s_ < kJogTopUmS) {
    speed_um_s_ = (uint16_t)(speed_um_s_ + kJogRampUmSPerMs);
  }
  if (inputs & hal::kJoyLeft) set_velocity(config::kAxisX, -1, limits, v_units);
  if (inputs & hal::kJoyRight) set_velocity(config::kAxisX, 1, limits, v_units);
  const uint8_t vertical = z_mode_ ? (uint8_t)config::kAxisZ : (uint8_t)config::kAxisY;
  if (inputs & hal::kJoyDown) set_velocity(vertical, -1, limits, v_units);
  if (inputs & hal::kJoyUp) set_velocity(vertical, 1, limits, v_units);
  return JogResult::kRunning;
}

}  // namespace app
