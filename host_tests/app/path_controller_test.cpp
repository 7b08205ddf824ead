// Path controller + planner on the kinematic plant: accuracy, job time, stops, hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "host_tests/app/motion_rig.h"

namespace fake_app {
namespace {

TEST(PathController, StraightMoveEndsOnTargetWithinOneMicrometre) {
  MotionRig rig;
  rig.queue({{20000, 5000, 0}});
  ASSERT_TRUE(rig.run_to_end(10000));
  const P3 p = rig.position_um();
  EXPECT_NEAR(p.x, 20000, 1.0);
  EXPECT_NEAR(p.y, 5000, 1.0);
}

TEST(PathController, ShallowLineKeepsItsDirectionDespiteCoarseVelocityUnits) {
  // dy/dx = 1/100: Y runs at ~100 um/s, about 7 native units of 14.9 um/s each.
  MotionRig rig;
  rig.plant.record = true;
  rig.queue({{50000, 500, 0}});
  ASSERT_TRUE(rig.run_to_end(20000));
  const double err = max_contour_error(rig.recorded_um(), {{0, 0, 0}, {50000, 500, 0}});
  EXPECT_LE(err, 2.0);
}

TEST(PathController, EmptyBufferGivesAControlledStopAtTheLastPoint) {
  MotionRig rig;
  rig.plant.record = true;
  // Three points, then nothing more: the controller must stop exactly at the third.
  const std::vector<P3> line{{0, 0, 0}, {4000, 0, 0}, {8000, 0, 0}, {12000, 0, 0}};
  rig.queue({line[1], line[2], line[3]});
  ASSERT_TRUE(rig.run_to_end(10000));
  double max_x = 0;
  for (const P3& p : rig.recorded_um()) max_x = std::max(max_x, p.x);
  EXPECT_LE(max_x, 12000 + 1.0);  // no overshoot beyond the end of the buffer
  EXPECT_NEAR(rig.position_um().x, 12000, 1.0);
}

TEST(PathController, StartAndStopRampWithinTheChipAcceleration) {
  // No jumps: on a straight move the command changes no faster than the chip ramps (13 native
  // units per ms) while the speed is above 2 mm/s. Below that, the last ~10 um, the discrete
  // braking curve and the exact stop may step by up to three ms of ramp (< 0.5 um of lag).
  MotionRig rig;
  rig.queue({{30000, 0, 0}});
  int max_step_fast = 0, max_step_slow = 0;
  int16_t last = 0;
  for (int i = 0; i < 10000; ++i) {
    rig.background();
    const bool fast = rig.controller.speed_um_s() > 2000;
    rig.tick();
    const int step = std::abs(rig.plant.v_target[0] - last);
    (fast ? max_step_fast : max_step_slow) = std::max(fast ? max_step_fast : max_step_slow, step);
    last = rig.plant.v_target[0];
    if (rig.controller.finished() && !rig.plant.moving()) break;
  }
  EXPECT_LE(max_step_fast, rig.plant.axis[0].accel_units_per_ms);
  EXPECT_LE(max_step_slow, 3 * rig.plant.axis[0].accel_units_per_ms);
  EXPECT_NEAR(rig.position_um().x, 30000, 1.0);
}

// A single long move at 2 mm/s stays on its line in every direction. The tick aims at the
// target again every ms, so a direction error of e (rad) leaves the tool about e times the
// remaining distance off the line: the direction and the per-axis speeds must keep their
// fraction bits (rounded down to whole micrometres and um/s they drifted 16-21 um here).
TEST(PathController, LongSlowMoveStaysOnItsLineInEveryDirection) {
  double worst = 0;
  for (int deg = 0; deg < 360; deg += 7) {
    MotionRig rig;
    rig.feed_um_s = 2000;
    rig.plant.record = true;
    const P3 start{100000, 100000, 0};
    rig.start_at(start);
    const double a = deg * 3.14159265358979 / 180.0;
    const P3 end{start.x + std::round(90000 * std::cos(a)),
                 start.y + std::round(90000 * std::sin(a)), 0};
    rig.queue({end});
    ASSERT_TRUE(rig.run_to_end(60000)) << deg;
    const double err = max_contour_error(rig.recorded_um(), {start, end});
    worst = std::max(worst, err);
    EXPECT_LE(err, 3.0) << deg << " degrees";
    EXPECT_NEAR(rig.position_um().x, end.x, 1.0) << deg;
    EXPECT_NEAR(rig.position_um().y, end.y, 1.0) << deg;
  }
  std::printf("[ metrics  ] long move at 2 mm/s: worst contour error %.2f um\n", worst);
}

TEST(PathController, StarvedRingStopsAndContinuesWhenPointsArrive) {
  MotionRig rig;
  rig.plant.record = true;
  rig.queue({{5000, 0, 0}});
  ASSERT_TRUE(rig.run_to_end(10000));
  rig.queue({{5000, 5000, 0}});
  ASSERT_TRUE(rig.run_to_end(10000));
  EXPECT_NEAR(rig.position_um().y, 5000, 1.0);
  const double err =
      max_contour_error(rig.recorded_um(), {{0, 0, 0}, {5000, 0, 0}, {5000, 5000, 0}});
  EXPECT_LE(err, 2.0);
}

TEST(PathController, HoldStopsOnThePathAndResumeFinishesTheJob) {
  MotionRig rig;
  rig.plant.record = true;
  const std::vector<P3> line = circle(20000, 0, 20000, 5);
  rig.start_at(line[0]);
  rig.queue(line);
  for (int i = 0; i < 1500; ++i) {
    rig.background();
    rig.tick();
  }
  rig.controller.set_hold(true);
  for (int i = 0; i < 500; ++i) {
    rig.background();
    rig.tick();
  }
  EXPECT_TRUE(rig.controller.at_rest());
  EXPECT_FALSE(rig.plant.moving());
  const P3 held = rig.position_um();
  for (int i = 0; i < 200; ++i) rig.tick();
  EXPECT_NEAR(rig.position_um().x, held.x, 0.01);  // nothing moves while held
  rig.controller.set_hold(false);
  ASSERT_TRUE(rig.run_to_end(30000));
  EXPECT_LE(max_contour_error(rig.recorded_um(), line), 10.0);
  EXPECT_NEAR(rig.position_um().x, line.back().x, 1.0);
}

// A hold on a curve of short chords (the resume tests' abort): the tool slows at the planned
// rate along the buffered points. Braking to the current target instead dropped the speed by
// several ramp steps in one tick and the chip's per-axis ramps slid the tool 33 um off.
TEST(PathController, HoldOnAFinelySampledCurveSlowsAtThePlannedRateAndStaysOnThePath) {
  MotionRig rig;
  rig.plant.record = true;
  const std::vector<P3> line = circle(20000, 20000, 2000, 1);  // 1 um chord error: short chords
  rig.start_at(line[0]);
  rig.queue(line);
  for (int i = 0; i < 600; ++i) {  // up to speed, part way round
    rig.background();
    rig.tick();
  }
  ASSERT_GT(rig.controller.speed_um_s(), 5000);
  ASSERT_FALSE(rig.controller.finished());
  rig.controller.set_hold(true);
  int max_drop = 0;
  for (int i = 0; i < 2000 && !(rig.controller.at_rest() && !rig.plant.moving()); ++i) {
    rig.background();
    const int before = rig.controller.speed_um_s();
    rig.tick();
    max_drop = std::max(max_drop, before - int(rig.controller.speed_um_s()));
  }
  ASSERT_TRUE(rig.controller.at_rest());
  EXPECT_FALSE(rig.plant.moving());
  EXPECT_FALSE(rig.controller.finished());  // stopped part way, not at the end of the circle
  EXPECT_LE(max_drop, int(rig.scaling.plan_accel_um_s_per_ms[0]));
  EXPECT_LE(max_contour_error(rig.recorded_um(), line), 5.0);
}

// The status's curve_point comes from this count: on a curve of more than 65 535 points it
// stays at 65 535 (the host then refuses to guess where the tool is), never wraps to a small
// number that would resume the job at the wrong place.
TEST(PathController, CurvePointCountSaturatesInsteadOfWrapping) {
  MotionRig rig;
  rig.pushes_per_tick = 16;
  rig.point_flags = app::kPointCurvePoint;
  std::vector<P3> line;
  for (int i = 1; i <= 66000; ++i) line.push_back({double(i) * 2, 0, 0});  // 2 um apart
  rig.queue(line);
  uint16_t highest = 0;
  bool went_down = false;
  for (long ms = 0; ms < 200000 && rig.controller.items_done() == 0; ++ms) {
    rig.background();
    rig.tick();
    if (rig.controller.items_done() != 0) break;
    const uint16_t n = rig.controller.item_points();
    if (n < highest) went_down = true;
    highest = std::max(highest, n);
  }
  EXPECT_EQ(rig.controller.items_done(), 1u);
  EXPECT_EQ(highest, 65535);
  EXPECT_FALSE(went_down);
}

TEST(PathController, OverrideOfFiftyPercentDoublesTheCruiseTime) {
  MotionRig full, half;
  half.controller.set_override_percent(50);
  full.queue({{60000, 0, 0}});
  half.queue({{60000, 0, 0}});
  ASSERT_TRUE(full.run_to_end(30000));
  ASSERT_TRUE(half.run_to_end(30000));
  EXPECT_NEAR(double(half.ms) / full.ms, 2.0, 0.05);
}

struct CurveCase {
  const char* name;
  std::vector<P3> line;
};

std::vector<CurveCase> curve_set() {
  return {
      {"circle_r20mm", circle(100000, 100000, 20000, 5)},
      {"circle_r2mm", circle(100000, 100000, 2000, 5)},
      {"square_40mm", square(50000, 50000, 40000)},
      {"star_5pt_r20mm", star(100000, 100000, 20000, 5)},
      {"zigzag_60deg", zigzag(20000, 100000, 10000, 60, 10)},
      {"sine_a5_p20", sine(20000, 100000, 5000, 20000, 100000, 500)},
  };
}

// The figures of docs/performance.md "Path controller and protocol": contour error and job
// time at 10 mm/s on the reference plant (chip ramp ~194 mm/s^2, 14.9 um/s per unit).
TEST(PathController, CurveSetAtTenMillimetresPerSecondMeetsErrorAndTimeTargets) {
  for (const CurveCase& c : curve_set()) {
    MotionRig rig;
    rig.start_at(c.line[0]);
    rig.plant.record = true;
    rig.queue(c.line);
    ASSERT_TRUE(rig.run_to_end(200000)) << c.name;
    const double err = max_contour_error(rig.recorded_um(), c.line);
    const double ideal_ms = polyline_length(c.line) / 10.0;  // um / (um/ms)
    const double ratio = rig.ms / ideal_ms;
    std::printf(
        "[ metrics  ] %-16s length %8.1f mm  points %5zu  error %5.2f um  time %7.3f s  x%.3f\n",
        c.name, polyline_length(c.line) / 1000, c.line.size(), err, rig.ms / 1000.0, ratio);
    EXPECT_LE(err, 10.0) << c.name;
    EXPECT_LE(ratio, 1.10) << c.name;
  }
}

}  // namespace
}  // namespace fake_app
