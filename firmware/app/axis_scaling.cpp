// Start-up unit conversions for the path controller (64-bit math only here, never per tick).
#include "firmware/app/axis_scaling.h"

#include "firmware/core/divide.h"       // div_u32_by_u16, div_u32_u16
#include "firmware/core/fixed_point.h"  // abs_u32, mul_u16_u16

namespace app {

namespace {

// floor(a m 2^shift / (b1 b2)) for b1 b2 > 0 (a m 2^shift < 2^64), saturated at 2^32 - 1:
// every 64-bit step of this file goes through here, out of line and with 32-bit arguments
// and result (64-bit code is long inline code on 8- and 16-bit cores).
__attribute__((noinline)) uint32_t mul_div(uint32_t a, uint32_t m, uint8_t shift, uint32_t b1,
                                           uint32_t b2) {
  const uint64_t q = (((uint64_t)a * m) << shift) / ((uint64_t)b1 * b2);
  return q > 0xFFFFFFFFULL ? 0xFFFFFFFFUL : (uint32_t)q;
}

// Largest shift <= 32 that brings floor(a 2^(base + shift) / (b1 b2)) below 2^16: the Q32
// value floor(a 2^(base + 32) / (b1 b2)) shifted right by 32 - shift, as a quotient of its
// own (the floor of a floor is the floor of the whole), so no 64-bit value leaves mul_div.
uint8_t fit_shift(uint32_t a, uint8_t base, uint32_t b1, uint32_t b2) {
  uint8_t shift = 32;
  while (shift > 0 && mul_div(a, 1, (uint8_t)(base + shift), b1, b2) > 65535UL) --shift;
  return shift;
}

// Saturates into 16 bits unsigned.
uint16_t sat_u16(uint32_t v) {
  return v > 65535UL ? (uint16_t)65535U : (uint16_t)v;
}

}  // namespace

// The fixed-point factors are the exact quotients floor(x 2^shift / y) for the largest
// shift (<= 32) that keeps every axis's factor in 16 bits.
bool build_axis_scaling(const config::MachineConfig& cfg, const hal::MotionAxes& motion,
                        AxisScaling* s) {
  bool ok = true;
  uint32_t ustep_s_per_unit_q16[config::kAxisCount];
  s->um_shift = 32;
  s->units_shift = 32;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    int32_t upm = config::usteps_per_mm(cfg.axis[a]);
    if (upm < 1) {
      upm = 1;
      ok = false;
    }
    if (upm > 65535L) {  // um_to_usteps divides 32/16 (a microstep of 15 nm: not an engraver)
      upm = 65535L;
      ok = false;
    }
    s->usteps_per_mm[a] = upm;
    uint32_t u = motion.usteps_per_s_per_unit_q16(a);
    if (u == 0) {
      u = 1;
      ok = false;
    }
    ustep_s_per_unit_q16[a] = u;
    // um per ustep = 1000 / upm; units per (um/s) = upm / 1000 / (usteps/s per unit).
    const uint8_t um_fit = fit_shift(1000, 0, (uint32_t)upm, 1);
    const uint8_t units_fit = fit_shift((uint32_t)upm, 16, u, 1000);
    if (um_fit < s->um_shift) s->um_shift = um_fit;
    if (units_fit < s->units_shift) s->units_shift = units_fit;
    int16_t vmax = motion.max_velocity_units(a);
    if (vmax < 1) {
      vmax = 1;
      ok = false;
    }
    s->max_units[a] = vmax;
    // um/s of v_max: vmax * usteps/s per unit / upm * 1000 (the q16 and upm as one divisor).
    const uint32_t chip_max_um_s = mul_div((uint32_t)vmax * 1000U, u, 0, (uint32_t)upm, 65536UL);
    uint32_t max_um_s = cfg.axis[a].max_speed_um_per_s;
    if (chip_max_um_s < max_um_s) max_um_s = chip_max_um_s;
    if (max_um_s > 32767UL) max_um_s = 32767UL;
    if (max_um_s < 1) max_um_s = 1;
    s->max_speed_um_s[a] = (uint16_t)max_um_s;
    // Held below 2^24: saturates the chip's and (with the configured limit < 2^23) the
    // planner's figure just as the exact value would, and keeps acc * 192 in 32 bits.
    uint32_t acc =
        mul_div((uint32_t)motion.accel_units_per_ms(a) * 1000U, u, 0, (uint32_t)upm, 65536UL);
    if (acc > 0xFFFFFFUL) acc = 0xFFFFFFUL;
    if (acc < 4) {
      acc = 4;
      ok = false;
    }
    s->chip_accel_um_s_per_ms[a] = sat_u16(acc);
    uint32_t plan = acc * kPlanAccelFraction256 / 256;
    // The configured axis acceleration is a limit too (the chip ramp may be set steeper).
    const uint32_t cfg_acc = cfg.axis[a].accel_um_per_s2 / 1000U;
    if (cfg_acc >= 1 && cfg_acc < plan) plan = cfg_acc;
    if (plan < 1) plan = 1;
    s->plan_accel_um_s_per_ms[a] = sat_u16(plan);
    s->travel_um[a] = cfg.axis[a].travel_um;
  }
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    const uint32_t upm = (uint32_t)s->usteps_per_mm[a];
    s->um_per_ustep_q[a] = (uint16_t)mul_div(1000, 1, s->um_shift, upm, 1);
    s->units_per_um_s_q[a] =
        (uint16_t)mul_div(upm, 1, (uint8_t)(16 + s->units_shift), ustep_s_per_unit_q16[a], 1000);
  }
  // The tick needs a microstep below 1 um (um_shift 16) for 15-bit direction vectors and
  // a native velocity unit above 1 um/s (units_shift >= 16 keeps products in 31 bits).
  if (s->um_shift < 16 || s->units_shift < 16) ok = false;
  return ok;
}

int32_t um_to_usteps(const AxisScaling& s, uint8_t axis, int32_t um) {
  // trunc(um * upm / 1000) = mm * upm + trunc(rest * upm / 1000), on |um| (the result is
  // odd in um). With upm < 2^16 (build_axis_scaling) both divisions are 32/16 with a
  // 16-bit quotient for |um| < 65 536 000: one DIV each on the dsPIC, no 32/32 division.
  const uint32_t upm = (uint32_t)s.usteps_per_mm[axis];
  const uint16_t upm16 = upm > 65535UL ? (uint16_t)65535U : (uint16_t)upm;
  const uint32_t a = core::abs_u32(um);
  uint16_t rest = 0;
  const uint32_t mm = core::div_u32_by_u16(a, 1000U, &rest);
  const uint32_t frac = core::div_u32_u16(core::mul_u16_u16(rest, upm16), 1000U, 0);
  const uint32_t whole = mm < 65536UL ? core::mul_u16_u16((uint16_t)mm, upm16) : mm * upm16;
  const uint32_t r = whole + frac;
  return um < 0 ? -(int32_t)r : (int32_t)r;
}

int32_t usteps_to_um(const AxisScaling& s, uint8_t axis, int32_t usteps) {
  const int32_t upm = s.usteps_per_mm[axis];
  const int32_t mm = usteps / upm;
  const int32_t rest = usteps % upm;
  return mm * 1000 + rest * 1000 / upm;
}

}  // namespace app
