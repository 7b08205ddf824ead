// The tick's integer helpers against wide references: normalisation, the capture test on
// squares, micrometres to microsteps with 32/16 divisions, and the velocity scale on a
// machine with fine microsteps (short direction vectors, where the scale loses bits).
#include <gtest/gtest.h>

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
