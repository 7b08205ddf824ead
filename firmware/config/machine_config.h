// Machine description in physical units: axes, travel, speeds, clocks.
// Drivers derive chip settings from it; the core derives unit conversions from it.
#ifndef FIRMWARE_CONFIG_MACHINE_CONFIG_H
#define FIRMWARE_CONFIG_MACHINE_CONFIG_H

#include <stdint.h>  // int32_t

namespace config {

enum { kAxisX = 0, kAxisY = 1, kAxisZ = 2, kAxisCount = 3 };

// Facts about the controller that the host learns from the session reply (*I); the host's
// defaults (work area, feeds) come from default_machine_config() below, never a copy.
enum {
  kFirmwareMajor = 0,
  kFirmwareMinor = 3,
  kLinkRxBufferBytes = 256  // the UART receive ring: 22 ms of input at 115200 Bd
};

struct AxisConfig {
  uint16_t full_steps_per_rev;   // motor, 200
  uint8_t microsteps_per_step;   // TMC428 usrs as a count: 16
  uint16_t pitch_um;             // lead screw travel per revolution
  int32_t travel_um;             // usable travel from the zero point
  uint32_t max_speed_um_per_s;   // fastest rapid
  uint32_t accel_um_per_s2;      // what the axis does without losing steps
  uint8_t run_current_eighths;   // 0 = 100 %, 1..7 = n/8 (TMC428 is_agtat/is_aleat)
  uint8_t hold_current_eighths;  // TMC428 is_v0
};

struct MachineConfig {
  AxisConfig axis[kAxisCount];
  uint32_t tmc428_clock_hz;    // shares the 10 MHz oscillator with the dsPIC crystal
  uint32_t spi_clock_hz;       // <= tmc428_clock_hz / 8
  uint16_t capture_radius_um;  // path controller switches target inside this
  uint32_t default_feed_um_per_s;
  uint32_t rapid_feed_um_per_s;
};

// The reference machine: A4 table, M8 lead screws (1.25 mm), 200-step motors at 16 usteps.
// One constant table copied (not a store per field: 0.3 kB less code on the AVR proxy).
inline MachineConfig default_machine_config() {
  static const MachineConfig c = {
      {
          {200, 16, 1250, 297000, 25000, 200000, 0, 4},  // X
          {200, 16, 1250, 210000, 25000, 200000, 0, 4},  // Y
          {200, 16, 1250, 40000, 5000, 50000, 0, 4},     // Z
      },
      10000000UL,  // tmc428_clock_hz
      1250000UL,   // spi_clock_hz
      10,          // capture_radius_um
      10000,       // default_feed_um_per_s
      25000,       // rapid_feed_um_per_s
  };
  return c;
}

// Microsteps per millimetre of an axis (2560 for the reference machine).
inline int32_t usteps_per_mm(const AxisConfig& a) {
  return (int32_t)((int32_t)a.full_steps_per_rev * a.microsteps_per_step * 1000L / a.pitch_um);
}

}  // namespace config

#endif  // FIRMWARE_CONFIG_MACHINE_CONFIG_H
