// Start-up unit conversions for the path controller (64-bit math only here, never per tick).
#include "firmware/app/axis_scaling.h"

#include "firmware/core/divide.h"       // div_u32_by_u16, div_u32_u16
#include "firmware/core/fixed_point.h"  // abs_u32, mul_u16_u16

namespace app {

namespace {

// Smallest shift >= 0 that brings every value of v below 2^16, given v as Q(max_shift).
uint8_t fit_shift(const uint64_t* v_q32, uint8_t n) {
  uint8_t shift = 32;
  for (uint8_t i = 0; i < n; ++i) {
    while (shift > 0 && (v_q32[i] >> (32 - shift)) >= 65536ULL) --shift;
  }
  return shift;
}

// Saturates a 64-bit value into 16 bits unsigned.
uint16_t sat_u16(uint64_t v) {
  return v > 65535ULL ? (uint16_t)65535U : (uint16_t)v;
}

}  // namespace

bool build_axis_scaling(const config::MachineConfig& cfg, const hal::MotionAxes& motion,
                        AxisScaling* s) {
  bool ok = true;
  uint64_t um_per_ustep_q32[config::kAxisCount];
  uint64_t units_per_um_s_q32[config::kAxisCount];
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
    um_per_ustep_q32[a] = (1000ULL << 32) / (uint64_t)upm;
    uint64_t ustep_s_per_unit_q16 = motion.usteps_per_s_per_unit_q16(a);
    if (ustep_s_per_unit_q16 == 0) {
      ustep_s_per_unit_q16 = 1;
      ok = false;
    }
    // units per (um/s) = upm / 1000 / (usteps/s per unit)
    units_per_um_s_q32[a] = ((uint64_t)upm << 32) * 65536ULL / 1000ULL / ustep_s_per_unit_q16;
    int16_t vmax = motion.max_velocity_units(a);
    if (vmax < 1) {
      vmax = 1;
      ok = false;
    }
    s->max_units[a] = vmax;
    // um/s of v_max: vmax * usteps/s per unit / upm * 1000
    uint64_t chip_max_um_s = (uint64_t)vmax * ustep_s_per_unit_q16 * 1000ULL / 65536ULL / upm;
    uint64_t max_um_s = cfg.axis[a].max_speed_um_per_s;
    if (chip_max_um_s < max_um_s) max_um_s = chip_max_um_s;
    if (max_um_s > 32767ULL) max_um_s = 32767ULL;
    if (max_um_s < 1) max_um_s = 1;
    s->max_speed_um_s[a] = (uint16_t)max_um_s;
    uint64_t acc =
        (uint64_t)motion.accel_units_per_ms(a) * ustep_s_per_unit_q16 * 1000ULL / 65536ULL / upm;
    if (acc < 4) {
      acc = 4;
      ok = false;
    }
    s->chip_accel_um_s_per_ms[a] = sat_u16(acc);
    uint64_t plan = acc * kPlanAccelFraction256 / 256;
    // The configured axis acceleration is a limit too (the chip ramp may be set steeper).
    uint64_t cfg_acc = cfg.axis[a].accel_um_per_s2 / 1000U;
    if (cfg_acc >= 1 && cfg_acc < plan) plan = cfg_acc;
    if (plan < 1) plan = 1;
    s->plan_accel_um_s_per_ms[a] = sat_u16(plan);
    s->travel_um[a] = cfg.axis[a].travel_um;
  }
  s->um_shift = fit_shift(um_per_ustep_q32, config::kAxisCount);
  s->units_shift = fit_shift(units_per_um_s_q32, config::kAxisCount);
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    s->um_per_ustep_q[a] = (uint16_t)(um_per_ustep_q32[a] >> (32 - s->um_shift));
    s->units_per_um_s_q[a] = (uint16_t)(units_per_um_s_q32[a] >> (32 - s->units_shift));
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
