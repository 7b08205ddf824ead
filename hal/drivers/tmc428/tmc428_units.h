// TMC428 settings from the machine's physical units: pulse_div, ramp_div, v_max, a_max,
// PMUL/PDIV, current scales, and the conversions the path controller needs.
// Integer only; the 64-bit arithmetic here runs once at init ([428DS] §8.11, §8.14).
#ifndef HAL_DRIVERS_TMC428_TMC428_UNITS_H
#define HAL_DRIVERS_TMC428_TMC428_UNITS_H

#include <stdint.h>  // uint32_t

#include "firmware/config/machine_config.h"  // config::AxisConfig

namespace drivers {
namespace tmc428 {

enum { kMaxVelocity = 2047, kMaxAMax = 2047, kMaxDiv = 13, kMaxClockHz = 16000000L };

// Why an axis configuration has no valid chip setting.
enum class SettingsError : uint8_t {
  kOk = 0,
  kBadClock = 1,       // f_clk 0 or above 16 MHz ([428DS] §5)
  kBadMicrosteps = 2,  // microsteps_per_step not 1, 2, 4 .. 64
  kBadMechanics = 3,   // zero steps/rev or pitch
  kSpeedTooHigh = 4,   // max speed above what pulse_div = 0, v = 2047 gives
  kSpeedZero = 5,      // max speed rounds to zero
  kAccelTooHigh = 6,   // a_max > 2047 even at ramp_div = 0
  kAccelTooLow = 7,    // a_max rounds to 0 even at ramp_div = 13
  kBadCurrent = 8,     // current scale above 7
  kSpiTooFast = 9      // SPI clock above f_clk / 8 ([428DS] §6.2 hint)
};

// Everything the driver writes for one motor, and what it tells the path controller.
struct AxisSettings {
  uint8_t pulse_div;  // 0..13
  uint8_t ramp_div;   // 0..13
  uint8_t usrs;       // log2(microsteps per full step)
  uint16_t v_min;     // 1 ([428DS] §8.3)
  uint16_t v_max;     // 1..2047
  uint16_t a_max;     // 1..2047
  uint8_t pmul;       // 128..255 (bit 7 is the forced register bit 15)
  uint8_t pdiv;       // 0..13
  uint8_t is_agtat;   // current scale while accelerating
  uint8_t is_aleat;   // current scale at constant speed
  uint8_t is_v0;      // current scale at standstill
  uint16_t a_threshold;
  uint32_t usteps_per_s_per_unit_q16;  // one velocity LSB in microsteps/s, Q16.16
  uint16_t accel_units_per_ms;         // velocity units the ramp adds per millisecond
};

// One velocity LSB in microsteps/s as Q16.16 = f_clk / 2^pulse_div, rounded: the pulse rate
// of velocity v is R = f_clk v / 2^(pulse_div+16) ([428DS] §8.14; 2^16 = 2048 * 32).
uint32_t usteps_per_s_per_unit_q16(uint32_t f_clk_hz, uint8_t pulse_div);

// Largest pulse_div (finest velocity LSB) whose v = 2047 still reaches rate_usteps_per_s;
// -1 if even pulse_div = 0 is too slow.
int8_t choose_pulse_div(uint32_t f_clk_hz, uint32_t rate_usteps_per_s);

// Smallest v whose rate is at least rate_usteps_per_s (clamped to 2047).
uint16_t velocity_for_rate(uint32_t f_clk_hz, uint32_t rate_usteps_per_s, uint8_t pulse_div);

// a_max giving accel_usteps_per_s2, rounded: a_max = dR 2^(pulse_div+ramp_div+29) / f_clk^2
// ([428DS] §8.14). Saturates at 65535.
uint32_t a_max_for_accel(uint32_t f_clk_hz, uint32_t accel_usteps_per_s2, uint8_t pulse_div,
                         uint8_t ramp_div);

// True if a_max is inside the [428DS] §8.7.1 bounds for |ramp_div - pulse_div| > 1.
bool a_max_allowed(uint16_t a_max, uint8_t pulse_div, uint8_t ramp_div);

// Smallest ramp_div whose a_max is >= 256 (ramp step <= 1 LSB per ramp clock, <= 0.2 %
// quantisation) and allowed; failing that the largest usable one. False if none.
bool choose_ramp_div(uint32_t f_clk_hz, uint32_t accel_usteps_per_s2, uint8_t pulse_div,
                     uint8_t* ramp_div, uint16_t* a_max);

// PMUL/PDIV for RAMP/SOFT mode with the data sheet's 5 % reduction: p = a_max /
// (128 2^(ramp_div-pulse_div)), pmul = int(0.95 p 8 2^pdiv) in 128..255, last such pdiv
// ([428DS] §8.11 and §19 pmulpdiv.c). False if no pdiv in 0..13 fits.
bool pmul_pdiv_for(uint16_t a_max, uint8_t ramp_div, uint8_t pulse_div, uint8_t* pmul,
                   uint8_t* pdiv);

// Velocity units per millisecond added by the ramp: a_max/256 per ramp clock, ramp clock =
// f_clk / 32 / 2^ramp_div. Rounded, at least 1.
uint16_t accel_units_per_ms(uint32_t f_clk_hz, uint16_t a_max, uint8_t ramp_div);

// Microsteps of an axis for a length in micrometres (rounded up when round_up).
uint32_t um_to_usteps(const config::AxisConfig& axis, uint32_t um, bool round_up);

// All chip settings for one axis.
SettingsError compute_axis_settings(const config::AxisConfig& axis, uint32_t f_clk_hz,
                                    AxisSettings* out);

}  // namespace tmc428
}  // namespace drivers

#endif  // HAL_DRIVERS_TMC428_TMC428_UNITS_H
