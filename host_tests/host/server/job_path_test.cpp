// The live preview's path: a plan's moves as pieces with their lengths, and where along
// them a machine position lies (a closed curve at its start is not done; never backwards).
#include <gtest/gtest.h>

#include "host/lib/server/job_path.h"
#include "host/lib/server/job_planning.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

// A full circle of radius 10 mm; the plan puts its lower-left corner at the zero: its centre
// at (10, 10), its start and end at (20, 10), reached by a rapid from the zero.
const char kCircle[] =
    "G21\nG90\nG0 Z2\nG0 X30 Y20\nG1 Z-0.1 F100\nG2 X30 Y20 I-10 J0 F600\nG0 Z2\n";

JobPlan circle_plan(const test::TempDir& dir) {
  const std::string file = (dir.path() / "circle.ngc").string();
  write_file(file, kCircle);
  return plan_file(file, "circle.ngc", JobPlanSettings{}, 200, 200);
}

int spline_step(const JobPlan& plan) {
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    if (plan.steps[i].kind == PlanStep::kSpline) return static_cast<int>(i);
  }
  return -1;
}

TEST(JobPath, PiecesFollowThePlanAndAddUpToItsLength) {
  test::TempDir dir;
  const JobPlan plan = circle_plan(dir);
  const nlohmann::json path = JobPath(plan).to_json();
  // Rapid to the circle, the circle (cut), rapid home.
  ASSERT_EQ(path["pieces"].size(), 3u) << path.dump();
  EXPECT_FALSE(path["pieces"][0]["pen_down"].get<bool>());
  EXPECT_TRUE(path["pieces"][1]["pen_down"].get<bool>());
  const double rapid_mm = std::hypot(20.0, 10.0);
  EXPECT_NEAR(path["pieces"][0]["length_mm"].get<double>(), rapid_mm, 0.001);
  EXPECT_NEAR(path["pieces"][1]["start_mm"].get<double>(), rapid_mm, 0.001);
  EXPECT_NEAR(path["pieces"][1]["length_mm"].get<double>(), 2 * M_PI * 10, 0.05);
  EXPECT_NEAR(path["length_mm"].get<double>(), 2 * rapid_mm + 2 * M_PI * 10, 0.05);
}

TEST(JobPath, AClosedCurveAtItsStartIsNotDoneAndProgressNeverGoesBack) {
  test::TempDir dir;
  const JobPlan plan = circle_plan(dir);
  JobPath path(plan);
  const int step = spline_step(plan);
  ASSERT_GE(step, 0);
  const double rapid_mm = std::hypot(20.0, 10.0);
  // At the circle's start (which is also its end): 0 mm into it.
  EXPECT_NEAR(path.advance(step, Point2(20, 10)), rapid_mm, 0.01);
  // Clockwise from (20, 10): a quarter at (10, 0), half at (0, 10).
  EXPECT_NEAR(path.advance(step, Point2(10, 0)), rapid_mm + M_PI * 5, 0.05);
  EXPECT_NEAR(path.advance(step, Point2(0, 10)), rapid_mm + M_PI * 10, 0.05);
  // A position reported behind (noise, a late status) leaves it where it was.
  const double d = 10 / std::sqrt(2.0);  // 3/8 of the way round
  EXPECT_NEAR(path.advance(step, Point2(10 - d, 10 - d)), rapid_mm + M_PI * 10, 0.05);
  // Back at the start after the whole circle: the circle is done.
  EXPECT_NEAR(path.advance(step, Point2(20, 10)), rapid_mm + 2 * M_PI * 10, 0.05);
  // Every command run: the whole path.
  EXPECT_DOUBLE_EQ(path.advance(-1, Point2(0, 0)), path.length_mm());
}

}  // namespace
}  // namespace host::server
