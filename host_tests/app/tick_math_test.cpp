// The tick's integer helpers against wide references: normalisation, the capture test on
// squares, micrometres to microsteps with 32/16 divisions, and the velocity scale on a
// machine with fine microsteps (short direction vectors, where the scale loses bits).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>

#include "firmware/app/axis_scaling.h"
#include "firmware/app/vector3.h"
#include "firmware/core/isqrt.h"
#include "host_tests/app/motion_rig.h"

namespace fake_app {
namespace {

// The normalisation as first written (shift loops, rounding by adding half): the reference.
void reference_normalise3(const int32_t d[3], int16_t out[3], int8_t* shift) {
  int64_t m = 0;
  for (int i = 0; i < 3; ++i) m = std::max<int64_t>(m, d[i] < 0 ? -(int64_t)d[i] : d[i]);
  if (m == 0) {
    out[0] = out[1] = out[2] = 0;
    *shift = 0;
    return;
  }
  int s = 0;
  while (m >= 32768) {
    m >>= 1;
    ++s;
  }
  while (m < 16384) {
    m <<= 1;
    --s;
  }
  for (int i = 0; i < 3; ++i) {
    int64_t v = s > 0 ? ((d[i] + ((int64_t)1 << (s - 1))) >> s) : ((int64_t)d[i] << -s);
    out[i] = (int16_t)std::min<int64_t>(v, 32767);
  }
  *shift = (int8_t)s;
}

TEST(TickMath, Normalise3EqualsTheReferenceOverTheWholeRange) {
  std::mt19937 rng(21);
  for (int i = 0; i < 500000; ++i) {
    int32_t d[3];
    for (int k = 0; k < 3; ++k) {
      const int32_t v = (int32_t)(rng() >> (rng() % 32));
      d[k] = (int32_t)(rng() & 1) ? -v : v;  // |v| < 2^31: INT32_MIN is not a distance
    }
    if (i % 5 == 0) d[2] = 0;
    int16_t want[3], got[3];
    int8_t want_shift = 0, got_shift = 0;
    reference_normalise3(d, want, &want_shift);
    app::normalise3(d, got, &got_shift);
    ASSERT_EQ(got_shift, want_shift) << d[0] << " " << d[1] << " " << d[2];
    for (int k = 0; k < 3; ++k) ASSERT_EQ(got[k], want[k]) << d[0] << " " << d[1] << " " << d[2];
  }
}

TEST(TickMath, CaptureTestOnSquaresAgreesWithTheRoot) {
  std::mt19937 rng(22);
  for (int i = 0; i < 1000000; ++i) {
    const uint32_t sum_sq = rng() % (3U << 30);
    const int8_t shift = (int8_t)((int)(rng() % 44) - 24);
    const uint32_t limit_q4 = rng() >> (rng() % 32);
    const bool want = app::scale_length_q4(core::isqrt32(sum_sq), shift) > limit_q4;
    ASSERT_EQ(app::length_q4_exceeds(sum_sq, shift, limit_q4), want)
        << sum_sq << " " << +shift << " " << limit_q4;
  }
  // Exactly at a square: the root equals the threshold there.
  for (uint32_t len = 1; len < 60000; len += 7) {
    const uint32_t sq = len * len;
    EXPECT_EQ(app::length_q4_exceeds(sq, -4, len), false);  // len > len: no
    EXPECT_EQ(app::length_q4_exceeds(sq, -4, len - 1), true);
  }
}

TEST(TickMath, UmToUstepsIsTheTruncatedQuotientForEveryMachine) {
  std::mt19937 rng(23);
  app::AxisScaling s{};
  for (int i = 0; i < 300000; ++i) {
    const int32_t upm = (int32_t)(1 + rng() % 65535);
    s.usteps_per_mm[0] = upm;
    const int64_t max_um = std::min<int64_t>(65535999, (int64_t)INT32_MAX * 1000 / upm);
    const int32_t um =
        (int32_t)((int64_t)(rng() % (uint64_t)(max_um + 1)) * ((rng() & 1) ? 1 : -1));
    const int64_t want = (int64_t)um * upm / 1000;  // C++ division truncates toward zero
    ASSERT_EQ(app::um_to_usteps(s, 0, um), want) << um << " um at " << upm << " usteps/mm";
  }
}

TEST(TickMath, ScalingRefusesMicrostepsBelowTheDivisionRange) {
  MotionRig rig;
  config::MachineConfig cfg = config::default_machine_config();
  cfg.axis[0].microsteps_per_step = 64;
  cfg.axis[0].pitch_um = 100;  // 128 000 usteps/mm: beyond the 32/16 division
  app::AxisScaling s{};
  EXPECT_FALSE(app::build_axis_scaling(cfg, rig.plant, &s));
  EXPECT_EQ(s.usteps_per_mm[0], 65535);
}

// build_axis_scaling against its plain 64-bit formulas (the code before its 64-bit steps
// went through one out-of-line helper) on random machines: every field equal.
TEST(TickMath, AxisScalingIsTheExact64BitQuotients) {
  std::mt19937_64 rng(22);
  auto pick = [&rng](uint64_t top) {
    const uint64_t v = rng() >> (rng() % 64);
    return rng() % 4 == 0 ? v % 16 : v % (top + 1);
  };
  for (int trial = 0; trial < 20000; ++trial) {
    config::MachineConfig cfg = config::default_machine_config();
    KinematicPlant plant;
    for (int a = 0; a < 3; ++a) {
      cfg.axis[a].microsteps_per_step = uint8_t(1u << (rng() % 7));
      cfg.axis[a].pitch_um = uint32_t(1 + pick(20000));
      cfg.axis[a].max_speed_um_per_s = uint32_t(pick(0xFFFFFFFFu));
      cfg.axis[a].accel_um_per_s2 = uint32_t(pick(0xFFFFFFFFu));
      plant.axis[a].usteps_per_s_per_unit_q16 = uint32_t(pick(0xFFFFFFFFu));
      plant.axis[a].max_units = int16_t(pick(0xFFFF));
      plant.axis[a].accel_units_per_ms = uint16_t(pick(0xFFFF));
    }
    app::AxisScaling s{};
    const bool ok = app::build_axis_scaling(cfg, plant, &s);
    bool ref_ok = true;
    uint64_t um_q32[3], units_q32[3];
    for (int a = 0; a < 3; ++a) {
      int64_t upm = config::usteps_per_mm(cfg.axis[a]);
      if (upm < 1 || upm > 65535) ref_ok = false;
      upm = std::min<int64_t>(std::max<int64_t>(upm, 1), 65535);
      ASSERT_EQ(s.usteps_per_mm[a], upm);
      uint64_t u = plant.axis[a].usteps_per_s_per_unit_q16;
      if (u == 0) u = 1, ref_ok = false;
      um_q32[a] = (1000ULL << 32) / uint64_t(upm);
      units_q32[a] = (uint64_t(upm) << 48) / 1000 / u;
      int64_t vmax = plant.axis[a].max_units;
      if (vmax < 1) vmax = 1, ref_ok = false;
      ASSERT_EQ(s.max_units[a], vmax);
      const uint64_t chip_max = uint64_t(vmax) * u * 1000 / 65536 / uint64_t(upm);
      const uint64_t max_um_s = std::max<uint64_t>(
          std::min<uint64_t>({chip_max, cfg.axis[a].max_speed_um_per_s, 32767}), 1);
      ASSERT_EQ(s.max_speed_um_s[a], max_um_s) << trial;
      uint64_t acc = uint64_t(plant.axis[a].accel_units_per_ms) * u * 1000 / 65536 / uint64_t(upm);
      if (acc < 4) acc = 4, ref_ok = false;
      ASSERT_EQ(s.chip_accel_um_s_per_ms[a], std::min<uint64_t>(acc, 65535)) << trial;
      uint64_t plan = acc * 192 / 256;
      const uint64_t cfg_acc = cfg.axis[a].accel_um_per_s2 / 1000;
      if (cfg_acc >= 1 && cfg_acc < plan) plan = cfg_acc;
      plan = std::min<uint64_t>(std::max<uint64_t>(plan, 1), 65535);
      ASSERT_EQ(s.plan_accel_um_s_per_ms[a], plan) << trial;
    }
    for (const bool units : {false, true}) {
      const uint64_t* v = units ? units_q32 : um_q32;
      int shift = 32;
      for (int a = 0; a < 3; ++a) {
        while (shift > 0 && (v[a] >> (32 - shift)) >= 65536) --shift;
      }
      ASSERT_EQ(units ? s.units_shift : s.um_shift, shift) << trial;
      for (int a = 0; a < 3; ++a) {
        ASSERT_EQ(units ? s.units_per_um_s_q[a] : s.um_per_ustep_q[a],
                  uint16_t(v[a] >> (32 - shift)))
            << trial;
      }
      if (shift < 16) ref_ok = false;
    }
    ASSERT_EQ(ok, ref_ok) << trial;
  }
}

TEST(TickMath, FineMicrostepsRunTheFeedAndEndOnTarget) {
  // 25 600 usteps/mm (0.04 um each) and a fast step clock (305 usteps/s per unit, so the
  // chip allows 24 mm/s): the direction vectors in um are short (about 640 to 1540), so at
  // 20 mm/s speed * 2^13 / len no longer fits 16 bits and the tick's scale keeps fewer
  // fraction bits. The speed and the end point must not suffer.
  MotionRig rig;
  for (int i = 0; i < 2; ++i) {
    rig.cfg.axis[i].microsteps_per_step = 64;
    rig.cfg.axis[i].pitch_um = 500;
    rig.plant.axis[i].usteps_per_s_per_unit_q16 = 20000000;
  }
  ASSERT_TRUE(app::build_axis_scaling(rig.cfg, rig.plant, &rig.scaling));
  rig.setup();
  rig.feed_um_s = 20000;
  ASSERT_GE(rig.scaling.max_speed_um_s[0], 20000);
  // The longest X component of a direction vector: below 20000 / 8 um/s.
  ASSERT_LT((32767L * rig.scaling.um_per_ustep_q[0]) >> rig.scaling.um_shift, 2500);
  rig.plant.record = true;
  rig.queue({{60000, 40000, 0}});
  ASSERT_TRUE(rig.run_to_end(20000));
  EXPECT_NEAR(rig.position_um().x, 60000, 1.0);
  EXPECT_NEAR(rig.position_um().y, 40000, 1.0);
  // 3.43 um measured (3.39 um with the former 32/32 division): the ramps at 20 mm/s.
  EXPECT_LE(max_contour_error(rig.recorded_um(), {{0, 0, 0}, {60000, 40000, 0}}), 4.0);
  const double ideal_ms = std::hypot(60000.0, 40000.0) / 20000.0 * 1000.0;
  EXPECT_LE(rig.ms, ideal_ms * 1.15);  // ramps included
}

}  // namespace
}  // namespace fake_app
