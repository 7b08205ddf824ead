// Planner: segment data, corner speeds, capture radii, and the backward pass that keeps a
// stop possible at the end of the buffer.
#include <gtest/gtest.h>

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
  // v^2 <= a_chip * e / (1 - cos 90) with e = 4 um.
  const double a_chip = rig.scaling.chip_accel_um_s_per_ms[0] * 1000.0;
  EXPECT_NEAR(rig.ring.newest(1)->junction_max_um_s, std::sqrt(a_chip * 4.0), 15.0);
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
