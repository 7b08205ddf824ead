// TMC428 unit conversions and per-axis settings (runs at init; 64-bit math allowed here).
#include "hal/drivers/tmc428/tmc428_units.h"  // declarations

namespace drivers {
namespace tmc428 {

enum Rounding { kFloor, kNearest, kCeil };

// (a m 2^shift) / (b 2^b_shift) for b > 0, rounded as asked (the numerator < 2^64).
// Every 64-bit step of this file goes through here: one copy of the 64-bit code (long
// inline code on 8- and 16-bit cores), called with 32-bit factors and shifts.
static __attribute__((noinline)) uint64_t div_shifted(uint64_t a, uint32_t m, uint8_t shift,
                                                      uint32_t b, uint8_t b_shift,
                                                      Rounding rounding) {
  const uint64_t num = (a * m) << shift;
  const uint64_t den = (uint64_t)b << b_shift;
  const uint64_t add = rounding == kCeil ? den - 1 : (rounding == kNearest ? den / 2 : 0);
  return (num + add) / den;
}

// The same for a 32-bit a, saturated at 2^32 - 1 (every caller but a_max_for_accel compares
// with 32-bit limits: no 64-bit compares at the call sites).
static __attribute__((noinline)) uint32_t div_shifted32(uint32_t a, uint32_t m, uint8_t shift,
                                                        uint32_t b, uint8_t b_shift,
                                                        Rounding rounding) {
  const uint64_t q = div_shifted(a, m, shift, b, b_shift, rounding);
  return q > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)q;
}

uint32_t usteps_per_s_per_unit_q16(uint32_t f_clk_hz, uint8_t pulse_div) {
  return div_shifted32(f_clk_hz, 1, 0, 1, pulse_div, kNearest);
}

int8_t choose_pulse_div(uint32_t f_clk_hz, uint32_t rate_usteps_per_s) {
  // 2047 f_clk / 2^(pd+16) >= rate  <=>  2047 f_clk >= rate 2^(pd+16)  <=>
  // floor(2047 f_clk / 2^(pd+16)) >= rate (rate an integer)
  for (int8_t pd = kMaxDiv; pd >= 0; --pd) {
    if (div_shifted32(kMaxVelocity, f_clk_hz, 0, 1, (uint8_t)(pd + 16), kFloor) >=
        rate_usteps_per_s) {
      return pd;
    }
  }
  return -1;
}

uint16_t velocity_for_rate(uint32_t f_clk_hz, uint32_t rate_usteps_per_s, uint8_t pulse_div) {
  const uint32_t v =
      div_shifted32(rate_usteps_per_s, 1, (uint8_t)(pulse_div + 16), f_clk_hz, 0, kCeil);
  return (uint16_t)(v > (uint32_t)kMaxVelocity ? (uint32_t)kMaxVelocity : v);
}

uint32_t a_max_for_accel(uint32_t f_clk_hz, uint32_t accel_usteps_per_s2, uint8_t pulse_div,
                         uint8_t ramp_div) {
  // Two stages so nothing overflows 64 bits: first the acceleration in velocity LSB per
  // second (Q8), accel 2^(pd+16) / f_clk, then per ramp clock times 256:
  // a_max = A 2^(rd+5) 256 / f_clk.
  const uint64_t a_q8 =
      div_shifted(accel_usteps_per_s2, 1, (uint8_t)(pulse_div + 24), f_clk_hz, 0, kNearest);
  if (a_q8 > (((uint64_t)1 << 62) >> (ramp_div + 5))) return 65535u;
  const uint64_t a_max = div_shifted(a_q8, 1, (uint8_t)(ramp_div + 5), f_clk_hz, 0, kNearest);
  return a_max > 65535u ? 65535u : (uint32_t)a_max;
}

bool a_max_allowed(uint16_t a_max, uint8_t pulse_div, uint8_t ramp_div) {
  if (a_max == 0 || a_max > kMaxAMax) return false;
  const int8_t d = (int8_t)(ramp_div - pulse_div);
  if (d >= -1 && d <= 1) return true;
  // [428DS] §8.7.1: 2^(d-1) <= a_max <= 2^(d+12) - 1
  if (d > 1 && a_max < ((uint32_t)1 << (d - 1))) return false;
  if (d + 12 < 0) return false;  // 2^(d+12) - 1 < 1 holds no a_max (and the shift is UB)
  if (d + 12 < 11 && a_max > ((uint32_t)1 << (d + 12)) - 1) return false;
  return true;
}

bool choose_ramp_div(uint32_t f_clk_hz, uint32_t accel_usteps_per_s2, uint8_t pulse_div,
                     uint8_t* ramp_div, uint16_t* a_max) {
  int8_t fallback = -1;
  uint16_t fallback_a = 0;
  for (uint8_t rd = 0; rd <= kMaxDiv; ++rd) {
    const uint32_t a = a_max_for_accel(f_clk_hz, accel_usteps_per_s2, pulse_div, rd);
    if (a > kMaxAMax) break;  // grows with rd
    if (!a_max_allowed((uint16_t)a, pulse_div, rd)) continue;
    if (a >= 256) {
      *ramp_div = rd;
      *a_max = (uint16_t)a;
      return true;
    }
    fallback = (int8_t)rd;
    fallback_a = (uint16_t)a;
  }
  if (fallback < 0) return false;
  *ramp_div = (uint8_t)fallback;
  *a_max = fallback_a;
  return true;
}

bool pmul_pdiv_for(uint16_t a_max, uint8_t ramp_div, uint8_t pulse_div, uint8_t* pmul,
                   uint8_t* pdiv) {
  // 0.95 p 8 2^pdiv = a_max 95 2^(pdiv+pd) / (100 2^(rd+4)), truncated like pmulpdiv.c.
  bool found = false;
  for (uint8_t pd = 0; pd <= kMaxDiv; ++pd) {
    const uint32_t value = div_shifted32((uint32_t)a_max * 95u, 1, (uint8_t)(pd + pulse_div), 100u,
                                         (uint8_t)(ramp_div + 4), kFloor);
    if (value >= 128 && value <= 255) {
      *pmul = (uint8_t)value;
      *pdiv = pd;
      found = true;
    }
  }
  return found;
}

uint16_t accel_units_per_ms(uint32_t f_clk_hz, uint16_t a_max, uint8_t ramp_div) {
  // a_max / 256 per ramp clock, f_clk / 2^(rd+5) ramp clocks per second, / 1000.
  const uint32_t units =
      div_shifted32(a_max, f_clk_hz, 0, 1000u, (uint8_t)(ramp_div + 13), kNearest);
  if (units == 0) return 1;
  return units > 65535u ? 65535u : (uint16_t)units;
}

uint32_t um_to_usteps(const config::AxisConfig& axis, uint32_t um, bool round_up) {
  return div_shifted32(um, (uint32_t)axis.full_steps_per_rev * axis.microsteps_per_step, 0,
                       axis.pitch_um, 0, round_up ? kCeil : kFloor);
}

// usrs for a microstep count (1, 2, 4 .. 64), -1 otherwise ([428DS] §8.14).
static int8_t usrs_for(uint8_t microsteps) {
  for (int8_t u = 0; u <= 6; ++u) {
    if (microsteps == (1u << u)) return u;
  }
  return -1;
}

SettingsError compute_axis_settings(const config::AxisConfig& axis, uint32_t f_clk_hz,
                                    AxisSettings* out) {
  if (f_clk_hz == 0 || f_clk_hz > (uint32_t)kMaxClockHz) return SettingsError::kBadClock;
  const int8_t usrs = usrs_for(axis.microsteps_per_step);
  if (usrs < 0) return SettingsError::kBadMicrosteps;
  if (axis.full_steps_per_rev == 0 || axis.pitch_um == 0) return SettingsError::kBadMechanics;
  if (axis.run_current_eighths > 7 || axis.hold_current_eighths > 7) {
    return SettingsError::kBadCurrent;
  }
  const uint32_t rate = um_to_usteps(axis, axis.max_speed_um_per_s, true);
  if (rate == 0) return SettingsError::kSpeedZero;
  const int8_t pulse_div = choose_pulse_div(f_clk_hz, rate);
  if (pulse_div < 0) return SettingsError::kSpeedTooHigh;
  const uint32_t accel = um_to_usteps(axis, axis.accel_um_per_s2, false);
  if (accel > ((uint32_t)1 << 26)) return SettingsError::kAccelTooHigh;
  AxisSettings s;
  s.pulse_div = (uint8_t)pulse_div;
  s.usrs = (uint8_t)usrs;
  s.v_min = 1;
  s.v_max = velocity_for_rate(f_clk_hz, rate, s.pulse_div);
  if (a_max_for_accel(f_clk_hz, accel, s.pulse_div, 0) > kMaxAMax) {
    return SettingsError::kAccelTooHigh;
  }
  if (!choose_ramp_div(f_clk_hz, accel, s.pulse_div, &s.ramp_div, &s.a_max)) {
    return SettingsError::kAccelTooLow;
  }
  if (!pmul_pdiv_for(s.a_max, s.ramp_div, s.pulse_div, &s.pmul, &s.pdiv)) {
    return SettingsError::kAccelTooLow;
  }
  // Run current whenever moving (a_threshold 0: |a| > 0 and |a| <= 0 both map to run),
  // hold current at standstill ([428DS] §8.9).
  s.is_agtat = axis.run_current_eighths;
  s.is_aleat = axis.run_current_eighths;
  s.is_v0 = axis.hold_current_eighths;
  s.a_threshold = 0;
  s.usteps_per_s_per_unit_q16 = usteps_per_s_per_unit_q16(f_clk_hz, s.pulse_div);
  s.accel_units_per_ms = accel_units_per_ms(f_clk_hz, s.a_max, s.ramp_div);
  *out = s;
  return SettingsError::kOk;
}

}  // namespace tmc428
}  // namespace drivers
