// TMC428 unit conversions against the data sheet formulas and worked examples.
#include <gtest/gtest.h>

#include <cmath>  // std::ldexp, std::fabs

#include "firmware/config/machine_config.h"
#include "hal/drivers/tmc428/tmc428_units.h"

namespace {

using namespace drivers::tmc428;

struct RateRow {
  uint32_t f_clk_hz;
  uint8_t pulse_div;
  double lsb_hz;  // tmc428.md §4 table, 4 significant digits
  double max_hz;
};

// R = f_clk v / (2^pulse_div 2048 32): the velocity quantisation table of tmc428.md §4, from
// the one velocity LSB the firmware uses (usteps_per_s_per_unit_q16 / 2^16).
TEST(Tmc428Units, PulseRateMatchesTheQuantisationTable) {
  const RateRow rows[] = {
      {10000000, 0, 152.6, 312300}, {10000000, 2, 38.15, 78090},  {10000000, 3, 19.07, 39040},
      {10000000, 4, 9.537, 19520},  {10000000, 5, 4.768, 9761},   {10000000, 6, 2.384, 4880},
      {16000000, 0, 244.1, 499800}, {16000000, 2, 61.04, 124900}, {16000000, 3, 30.52, 62470},
      {16000000, 4, 15.26, 31230},  {16000000, 5, 7.629, 15620},  {16000000, 6, 3.815, 7809},
  };
  for (const RateRow& r : rows) {
    SCOPED_TRACE(testing::Message() << r.f_clk_hz << " Hz pulse_div " << int(r.pulse_div));
    // The table prints 4 significant digits: agree within 0.05 %.
    const double lsb_hz = usteps_per_s_per_unit_q16(r.f_clk_hz, r.pulse_div) / 65536.0;
    EXPECT_NEAR(lsb_hz, r.lsb_hz, r.lsb_hz * 5e-4);
    EXPECT_NEAR(lsb_hz * 2047, r.max_hz, r.max_hz * 5e-4);
  }
}

TEST(Tmc428Units, OneVelocityUnitInQ16IsTheClockOverTwoToThePulseDiv) {
  // 38.147 usteps/s * 65536 = 2 500 000 at 10 MHz, pulse_div 2.
  EXPECT_EQ(usteps_per_s_per_unit_q16(10000000, 2), 2500000u);
  EXPECT_EQ(usteps_per_s_per_unit_q16(10000000, 4), 625000u);
}

TEST(Tmc428Units, PicksTheFinestPulseDivThatStillReachesTheRate) {
  // 64000 usteps/s: pulse_div 2 reaches 78.09 kHz, 3 only 39.04 kHz.
  EXPECT_EQ(choose_pulse_div(10000000, 64000), 2);
  // 12800 usteps/s: pulse_div 4 reaches 19.52 kHz, 5 only 9.761 kHz.
  EXPECT_EQ(choose_pulse_div(10000000, 12800), 4);
  // Exactly the pulse_div 0 maximum is reachable, one more is not.
  EXPECT_EQ(choose_pulse_div(10000000, 312347), 0);
  EXPECT_EQ(choose_pulse_div(10000000, 312348), -1);
}

TEST(Tmc428Units, VelocityForARateRoundsUpSoTheMaximumIsReached) {
  // 64000 * 2^18 / 10^7 = 1677.7 -> 1678.
  EXPECT_EQ(velocity_for_rate(10000000, 64000, 2), 1678);
  EXPECT_EQ(velocity_for_rate(10000000, 10000000, 0), 2047);  // clamped
}

TEST(Tmc428Units, AMaxFollowsTheAccelerationFormula) {
  // dR = f_clk^2 a_max / 2^(pd+rd+29): 512000 usteps/s^2 at pd 2, rd 5:
  // a_max = 512000 * 2^36 / 10^14 = 351.8 -> 352.
  EXPECT_EQ(a_max_for_accel(10000000, 512000, 2, 5), 352u);
  // And back (the data sheet's formula): 10^14 * 352 / 2^36 = 512227.4, 351 gives 510772.2:
  // 352 is the nearest.
  const double accel_352 = 1e14 * 352 / std::ldexp(1.0, 36);
  const double accel_351 = 1e14 * 351 / std::ldexp(1.0, 36);
  EXPECT_NEAR(accel_352, 512227.4, 0.05);
  EXPECT_LT(std::fabs(accel_352 - 512000), std::fabs(accel_351 - 512000));
  // 16 MHz, pd = rd = 0, a_max 1: 2.56e14 / 2^29 = 476837.2 usteps/s^2.
  EXPECT_EQ(a_max_for_accel(16000000, 476837, 0, 0), 1u);
}

TEST(Tmc428Units, RampDivIsTheSmallestGivingAMaxOfAtLeast256) {
  uint8_t rd = 0;
  uint16_t a_max = 0;
  ASSERT_TRUE(choose_ramp_div(10000000, 512000, 2, &rd, &a_max));
  // rd 4 gives 175.9, rd 5 gives 351.8.
  EXPECT_EQ(rd, 5);
  EXPECT_EQ(a_max, 352);
}

TEST(Tmc428Units, PmulPdivWorkedExample) {
  // tmc428.md §4: a_max 1000, ramp_div = pulse_div: p = 7.8125, 0.95 p = 7.42,
  // pdiv 2 -> 7.42 * 32 = 237.5 -> p_mul 237 = 0xED.
  uint8_t pmul = 0;
  uint8_t pdiv = 0;
  ASSERT_TRUE(pmul_pdiv_for(1000, 3, 3, &pmul, &pdiv));
  EXPECT_EQ(pmul, 0xED);
  EXPECT_EQ(pdiv, 2);
}

TEST(Tmc428Units, PmulPdivForTheReferenceMachine) {
  // a_max 352, rd 5, pd 2: p = 352 / (128 * 8) = 0.34375, 0.95 p = 0.3266;
  // * 8 * 2^pdiv in 128..255 -> pdiv 6: 167.2 -> 167.
  uint8_t pmul = 0;
  uint8_t pdiv = 0;
  ASSERT_TRUE(pmul_pdiv_for(352, 5, 2, &pmul, &pdiv));
  EXPECT_EQ(pmul, 167);
  EXPECT_EQ(pdiv, 6);
}

TEST(Tmc428Units, AMaxBoundsOfSection871) {
  // |rd - pd| > 1: 2^(rd-pd-1) <= a_max <= 2^(rd-pd+12) - 1.
  EXPECT_FALSE(a_max_allowed(7, 0, 4));  // needs >= 8
  EXPECT_TRUE(a_max_allowed(8, 0, 4));
  EXPECT_TRUE(a_max_allowed(1023, 4, 2));  // 2^10 - 1
  EXPECT_FALSE(a_max_allowed(1024, 4, 2));
  EXPECT_FALSE(a_max_allowed(0, 2, 2));
}

TEST(Tmc428Units, NoAMaxFitsWhenPulseDivExceedsRampDivByMoreThan12) {
  // rd - pd + 12 = -1: the upper bound 2^(rd-pd+12) - 1 is below 1.
  EXPECT_FALSE(a_max_allowed(1, 13, 0));
}

TEST(Tmc428Units, AccelUnitsPerMillisecond) {
  // a_max / 256 per ramp clock, 10 MHz / 32 / 2^5 = 9765.6 ramp clocks/s:
  // 352 / 256 * 9.7656 = 13.43 -> 13.
  EXPECT_EQ(accel_units_per_ms(10000000, 352, 5), 13);
  EXPECT_EQ(accel_units_per_ms(10000000, 1, 13), 1);  // never 0
}

TEST(Tmc428Units, ReferenceAxisSettings) {
  const config::MachineConfig cfg = config::default_machine_config();
  AxisSettings s;
  ASSERT_EQ(compute_axis_settings(cfg.axis[config::kAxisX], cfg.tmc428_clock_hz, &s),
            SettingsError::kOk);
  EXPECT_EQ(s.pulse_div, 2);
  EXPECT_EQ(s.ramp_div, 5);
  EXPECT_EQ(s.usrs, 4);
  EXPECT_EQ(s.v_max, 1678);
  EXPECT_EQ(s.a_max, 352);
  EXPECT_EQ(s.v_min, 1);
  EXPECT_EQ(s.is_v0, 4);
}

TEST(Tmc428Units, RejectsMicrostepsThatAreNotAPowerOfTwo) {
  config::AxisConfig a = config::default_machine_config().axis[0];
  a.microsteps_per_step = 12;
  AxisSettings s;
  EXPECT_EQ(compute_axis_settings(a, 10000000, &s), SettingsError::kBadMicrosteps);
}

TEST(Tmc428Units, RejectsAClockAbove16MHz) {
  const config::AxisConfig a = config::default_machine_config().axis[0];
  AxisSettings s;
  EXPECT_EQ(compute_axis_settings(a, 20000000, &s), SettingsError::kBadClock);
}

TEST(Tmc428Units, RejectsAnAccelerationBeyondAMax2047AtRampDiv0) {
  config::AxisConfig a = config::default_machine_config().axis[0];
  a.accel_um_per_s2 = 2000000000;  // 2000 m/s^2
  AxisSettings s;
  EXPECT_EQ(compute_axis_settings(a, 10000000, &s), SettingsError::kAccelTooHigh);
}

TEST(Tmc428Units, RejectsZeroPitch) {
  config::AxisConfig a = config::default_machine_config().axis[0];
  a.pitch_um = 0;
  AxisSettings s;
  EXPECT_EQ(compute_axis_settings(a, 10000000, &s), SettingsError::kBadMechanics);
}

}  // namespace
