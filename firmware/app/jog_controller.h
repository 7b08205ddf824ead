// Manual zeroing in the 1 ms tick: joystick jog with a speed that ramps up while a direction
// is held, the Z button toggling the joystick's up/down between Y and Z, confirm setting the
// zero of the chosen axes, clear cancelling. Output is native velocities; no I/O here.
#ifndef FIRMWARE_APP_JOG_CONTROLLER_H
#define FIRMWARE_APP_JOG_CONTROLLER_H

#include <stdint.h>  // int32_t, int16_t

#include "firmware/app/axis_scaling.h"  // AxisScaling

namespace app {

enum class JogResult : uint8_t {
  kRunning = 0,
  kConfirmed = 1,  // stopped; zero_usteps() holds the new x_actual values to write
  kCancelled = 2   // stopped; nothing changes
};

// Jog speeds, um/s: start, ramp per millisecond held, top.
static const uint16_t kJogStartUmS = 200;
static const uint16_t kJogRampUmSPerMs = 2;
static const uint16_t kJogTopUmS = 5000;
// The machine counts as stopped after this many ticks without a position change.
static const uint8_t kJogSettleTicks = 5;

class JogController {
 public:
  JogController();
  void init(const AxisScaling& scaling);
  // Begins zeroing the axes in mask (bit0 X, bit1 Y, bit2 Z); inputs is the current
  // button state (buttons already down are ignored until released).
  void start(uint8_t axes_mask, uint8_t inputs);
  // One tick: inputs (hal::InputBits), limits (hal::LimitBits), actual positions.
  JogResult tick(uint8_t inputs, uint8_t limits, const int32_t pos_usteps[config::kAxisCount],
                 int16_t v_units[config::kAxisCount]);
  // After kConfirmed: x_actual to write (0 on the zeroed axes, unchanged elsewhere).
  const int32_t* zero_usteps() const { return zero_usteps_; }
  bool z_mode() const { return z_mode_; }
  uint16_t speed_um_s() const { return speed_um_s_; }

 private:
  enum Phase { kJogging, kSettling };
  void set_velocity(uint8_t axis, int8_t sign, uint8_t limits, int16_t v_units[3]) const;

  AxisScaling scaling_;
  int32_t last_pos_[config::kAxisCount];
  int32_t zero_usteps_[config::kAxisCount];
  uint16_t speed_um_s_;
  uint8_t axes_mask_;
  uint8_t prev_inputs_;
  uint8_t still_ticks_;
  uint8_t phase_;
  bool confirm_;
  bool z_mode_;
};

}  // namespace app

#endif  // FIRMWARE_APP_JOG_CONTROLLER_H
