// What the path controller and machine state need from the motion controller chip.
// Implemented by the TMC428 driver (hal/drivers) and by host plants/models (hal/fake).
#ifndef HAL_INTERFACES_MOTION_AXES_H
#define HAL_INTERFACES_MOTION_AXES_H

#include <stdint.h>  // int32_t

#include "firmware/config/machine_config.h"

namespace hal {

// Limit switch bits as read from the chip: left (negative end) and right (positive end).
enum LimitBits {
  kLimitXLeft = 0x01,
  kLimitXRight = 0x02,
  kLimitYLeft = 0x04,
  kLimitYRight = 0x08,
  kLimitZLeft = 0x10,
  kLimitZRight = 0x20
};

// Outcome of one step of the power drivers' status check (MotionAxes::poll_driver_check).
enum DriverCheck {
  kDriverCheckPending = 0,      // no fresh status yet (or the chip has no status read-back)
  kDriverCheckOk = 1,           // a fresh status of every driver, no fault
  kDriverCheckFault = 2,        // overtemperature, overcurrent/short, or the chain is broken
  kDriverCheckUndervoltage = 3  // motor supply too low on a driver (e-stop or supply lost)
};

class MotionAxes {
 public:
  // x_actual of X, Y, Z in microsteps. False if the chip did not answer sanely.
  virtual bool read_actual_usteps(int32_t out[config::kAxisCount]) = 0;
  // v_target of X, Y, Z in the chip's native signed units (TMC428: -2047..2047).
  virtual bool write_velocity_units(const int16_t v[config::kAxisCount]) = 0;
  // v_actual in native units (what the chip's ramp has reached).
  virtual bool read_velocity_units(int16_t out[config::kAxisCount]) = 0;
  // Sets x_actual (zeroing). Only while the axes stand still.
  virtual bool set_actual_usteps(const int32_t usteps[config::kAxisCount]) = 0;
  // Active limit switches as LimitBits.
  virtual bool read_limits(uint8_t* bits) = 0;
  // Microsteps per second of one native velocity unit on an axis, Q16.16.
  virtual uint32_t usteps_per_s_per_unit_q16(uint8_t axis) const = 0;
  // Largest native velocity magnitude the chip takes (TMC428 v_max, <= 2047).
  virtual int16_t max_velocity_units(uint8_t axis) const = 0;
  // Native velocity units the chip's ramp adds per millisecond (a_max translated).
  virtual uint16_t accel_units_per_ms(uint8_t axis) const = 0;
  // One step of a non-blocking check of the power drivers' status (DriverCheck), short
  // enough for the 1 ms tick (at most one bus transaction); call it every few ms. Chips
  // without a driver status read-back keep this default.
  virtual uint8_t poll_driver_check() { return kDriverCheckPending; }

 protected:
  ~MotionAxes() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_MOTION_AXES_H
