// Planner: segment data, corner speeds, capture radii, and the backward pass that keeps a
// stop possible at the end of the buffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "host_tests/app/motion_rig.h"

namespace fake_app {
namespace {

TEST(Planner, ReachSpeedIsTheSquareRootOfExitSquaredPlusTwoAL) {
  // exit 1000 um/s, a = 150 (um/s)/ms = 150000 um/s^2, L = 2000 um.
  const double expected = std::sqrt(1000.0 * 1000.0 + 2 * 150000.0 * 2000.0);
  EXPECT_NEAR(app::reach_speed_um_s(1000, 150, 2000), expected, 1.0);
  EXPECT_EQ(app::reach_speed_um_s(0, 150, 0), 0);
  EXPECT_EQ(app::reach_speed_um_s(0, 150, 100000000), 32767);  // saturates, no overflow
}

TEST(Planner, NewestPointIsAlwaysPlannedToEndAtRest) {
  MotionRig rig;
  const int32_t p1[3] = {10000, 0, 0};
  const int32_t p2[3] = {10100, 0, 0};
  ASSERT_TRUE(rig.planner.push(&rig.ring, p1, 10000, 0, 0));
  ASSERT_TRUE(rig.planner.push(&rig.ring, p2, 10000, 0, 0));
  const app::PlanEntry* newest = rig.ring.newest(0);
  const double a = newest->accel_um_s_per_ms * 1000.0;
  // Entering the last 100 um no faster than a stop within those 100 um allows.
  EXPECT_LE(newest->entry_max_um_s, std::sqrt(2 * a * 100) + 1);
}

TEST(Planner, AppendingOnlyEverRaisesThePlannedSpeeds) {
  MotionRig rig;
  std::vector<uint16_t> before;
  for (int i = 1; i <= 20; ++i) {
    const int32_t p[3] = {i * 300, (i % 3) * 200, 0};
    ASSERT_TRUE(rig.planner.push(&rig.ring, p, 10000, 0, 0));
    const uint16_t n = rig.ring.size();
    for (uint16_t k = 1; k < n; ++k) {  // k-th newest now was (k-1)-th newest before
      EXPECT_GE(rig.ring.newest(k)->entry_max_um_s, before[k - 1]) << "point " << i;
    }
    before.clear();
    for (uint16_t k = 0; k < n; ++k) before.push_back(uint16_t(rig.ring.newest(k)->entry_max_um_s));
  }
}

TEST(Planner, RightAngleCornerSpeedKeepsTheRampErrorWithinFourMicrometres) {
  MotionRig rig;
  const int32_t a[3] = {20000, 0, 0};
  const int32_t b[3] = {20000, 20000, 0};
  const int32_t c[3] = {20000, 20001, 0};
  rig.planner.push(&rig.ring, a, 10000, 0, 0);
  rig.planner.push(&rig.ring, b, 10000, 0, 0);
  rig.planner.push(&rig.ring, c, 10000, 0, 0);
  // v^2 <= a e / (1 - cos 90) with e = 4 um and a what the chip's ramp has left along the
  // velocity step while the tick speeds up along the new direction: a_chip - a_plan sin 45.
  const double a_spare = (rig.scaling.chip_accel_um_s_per_ms[0] -
                          rig.scaling.plan_accel_um_s_per_ms[0] * std::sqrt(0.5)) *
                         1000.0;
  EXPECT_NEAR(rig.ring.newest(1)->junction_max_um_s, std::sqrt(a_spare * 4.0), 15.0);
}

// Points every L on a circle of radius R: each corner alone is gentle, but together they are
// a curve that needs v^2 / R of acceleration. The junction speeds keep it within what the
// chip's ramp has left beside the planned tangential acceleration: sqrt(a_chip^2 - a_plan^2).
TEST(Planner, PointsOnATightCircleAreLimitedToTheCentripetalSpeed) {
  for (const double radius_um : {100.0, 250.0, 1000.0}) {
    MotionRig rig;
    const double step_rad = radius_um < 500 ? 0.2 : 0.1;  // chords of 20 to 100 um
    const int n = 30;
    for (int i = 0; i <= n; ++i) {
      const double t = i * step_rad;
      const int32_t p[3] = {int32_t(std::lround(10000 + radius_um * std::sin(t))),
                            int32_t(std::lround(10000 - radius_um * std::cos(t))), 0};
      ASSERT_TRUE(rig.planner.push(&rig.ring, p, 30000, 0, 0));
    }
    const double chip = rig.scaling.chip_accel_um_s_per_ms[0] * 1000.0;
    const double plan = rig.scaling.plan_accel_um_s_per_ms[0] * 1000.0;
    const double a_n = std::sqrt(chip * chip - plan * plan);
    // The chord's circle: L = 2 R sin(step / 2), R' = L / (2 sin(step / 2)) = R.
    // Each corner alone: v^2 <= (a_chip - a_plan sin(step / 2)) e / (1 - cos step), e = 4 um.
    const double a_corner = chip - plan * std::sin(step_rad / 2);
    const double v_corner = std::sqrt(a_corner * 4.0 / (1 - std::cos(step_rad)));
    const double v_max = std::min(std::sqrt(a_n * radius_um), v_corner);
    ASSERT_LT(v_max, 0.95 * v_corner);  // the curve speed is what is tested
    // Points rounded to whole micrometres turn each chord by up to 1 um / L: at R = 100 um
    // (L = 20 um) single corners scatter by ~20 %, their mean by little.
    double sum = 0;
    for (int k = 2; k < n - 2; ++k) {  // interior corners (the ends are the ring's stops)
      const double v = rig.ring.newest(uint16_t(k))->junction_max_um_s;
      EXPECT_LE(v, v_max * 1.25) << "R " << radius_um << " um, corner " << k;
      EXPECT_GE(v, v_max * 0.75) << "R " << radius_um << " um, corner " << k;
      sum += v;
    }
    EXPECT_NEAR(sum / (n - 4), v_max, 0.05 * v_max) << "R " << radius_um << " um";
  }
}

// A jog: a turn left, a few micrometres, the same turn back right (two drawn lines chained
// across a small gap make one). Priced alone each corner keeps its ramp error within the
// corner tolerance, but the chip's lag from the first has not died out at the second, so the
// second is priced as one corner whose velocity step is both: 2 sin(theta/2) summed. Between
// turns farther apart than two capture radii (20 um), each corner alone.
TEST(Planner, AJogsSecondTurnIsPricedWithBothTurnsVelocitySteps) {
  const double chip = MotionRig().scaling.chip_accel_um_s_per_ms[0] * 1000.0;
  const double plan = MotionRig().scaling.plan_accel_um_s_per_ms[0] * 1000.0;
  for (const int32_t middle_um : {8, 19, 40}) {
    MotionRig rig;
    const double t = 40 * M_PI / 180;
    const int32_t p0[3] = {10000, 10000, 0};
    const int32_t a[3] = {12000, 10000, 0};
    const int32_t b[3] = {a[0] + int32_t(std::lround(middle_um * std::cos(t))),
                          a[1] + int32_t(std::lround(middle_um * std::sin(t))), 0};
    const int32_t c[3] = {b[0] + 2000, b[1], 0};
    for (const int32_t* p : {p0, a, b, c}) ASSERT_TRUE(rig.planner.push(&rig.ring, p, 30000, 0, 0));
    // The turn of the rounded middle segment, the same both ways (the outer ones run along x).
    const double turn = std::atan2(double(b[1] - a[1]), double(b[0] - a[0]));
    const double v_alone =
        std::sqrt((chip - plan * std::sin(turn / 2)) * 4.0 / (1 - std::cos(turn)));
    const double s = 2 * std::sin(turn / 2);  // both velocity steps, over 2 v
    const double v_jog = std::sqrt((chip - plan * s) * 4.0 / (2 * s * s));
    // Both corners are also on a curve of radius L / (2 sin(theta/2)) (the curve speed).
    const double a_n = std::sqrt(chip * chip - plan * plan);
    const double middle = std::hypot(double(b[0] - a[0]), double(b[1] - a[1]));
    const double v_each = std::min(v_alone, std::sqrt(a_n * middle / (2 * std::sin(turn / 2))));
    const double v = rig.ring.newest(0)->junction_max_um_s;        // at b, where c's segment starts
    const double v_first = rig.ring.newest(1)->junction_max_um_s;  // at a: the first turn alone
    EXPECT_NEAR(v_first, v_each, 0.02 * v_each) << middle_um << " um";
    if (middle_um < 20) {
      ASSERT_LT(v_jog, 0.8 * v_each);  // what the test tells apart
      EXPECT_NEAR(v, v_jog, 0.02 * v_jog) << middle_um << " um";
    } else {
      EXPECT_NEAR(v, v_each, 0.02 * v_each) << middle_um << " um";
    }
  }
}

TEST(Planner, StraightChainsAndZeroLengthPointsGetNoCurveLimit) {
  MotionRig rig;
  // Collinear points 10 um apart with a repeated point among them: no turn, no limit below
  // the feed (the ring's last entries stop, the first starts at rest).
  const int32_t xs[] = {1000, 1010, 1020, 1020, 1030, 1040, 1050, 1060};
  for (const int32_t x : xs) {
    const int32_t p[3] = {x, 2000, 0};
    ASSERT_TRUE(rig.planner.push(&rig.ring, p, 5000, 0, 0));
  }
  for (uint16_t k = 1; k + 2 < rig.ring.size(); ++k)
    EXPECT_EQ(rig.ring.newest(k)->junction_max_um_s, 5000u * 2) << k;  // feed x 200 % override
}

TEST(Planner, CaptureRadiusIsTheConfiguredTenOnStraightsAndSmallAtCorners) {
  MotionRig rig;
  const int32_t a[3] = {10000, 0, 0};
  const int32_t b[3] = {20000, 0, 0};      // straight on
  const int32_t c[3] = {20000, 10000, 0};  // then 90 degrees
  const int32_t d[3] = {20000, 10001, 0};
  rig.planner.push(&rig.ring, a, 10000, 0, 0);
  rig.planner.push(&rig.ring, b, 10000, 0, 0);
  rig.planner.push(&rig.ring, c, 10000, 0, 0);
  rig.planner.push(&rig.ring, d, 10000, 0, 0);
  EXPECT_EQ(rig.ring.newest(3)->capture_um, 10);  // a: straight continuation
  EXPECT_EQ(rig.ring.newest(2)->capture_um, 2);   // b: 90 degree corner, cut 2 um
}

TEST(Planner, FullRingRefusesThePointAndChangesNothing) {
  MotionRig rig;
  for (int i = 1; i <= int(app::CoordinateRing::capacity()); ++i) {
    const int32_t p[3] = {i * 100, 0, 0};
    ASSERT_TRUE(rig.planner.push(&rig.ring, p, 10000, 0, 0));
  }
  const int32_t extra[3] = {999999, 0, 0};
  EXPECT_FALSE(rig.planner.push(&rig.ring, extra, 10000, 0, 0));
  EXPECT_EQ(rig.planner.last_um()[0], int32_t(app::CoordinateRing::capacity()) * 100);
}

TEST(AxisScaling, ReferenceMachineConversions) {
  MotionRig rig;
  EXPECT_EQ(app::um_to_usteps(rig.scaling, 0, 1000), 2560);
  EXPECT_EQ(app::um_to_usteps(rig.scaling, 0, -297000), -760320);
  EXPECT_EQ(app::usteps_to_um(rig.scaling, 0, 2560), 1000);
  // 25 mm/s rapid is within the chip's v_max at 14.9 um/s per unit (2047 units = 30.5 mm/s).
  EXPECT_EQ(rig.scaling.max_speed_um_s[0], 25000);
}

}  // namespace
}  // namespace fake_app
