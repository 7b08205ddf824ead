// The live preview's path: a plan's moves as pieces with their lengths, and where along
// them a machine position lies (a closed curve at its start is not done; never backwards).
#include <gtest/gtest.h>

#include "host/lib/drawing/conics.h"  // line_spline, polyline_spline
#include "host/lib/plan/tool_path_walk.h"
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

// n separate 2.2 mm lines on a grid: two moves each in X/Y (the travel to it, the cut).
JobPlan separate_lines(int n) {
  Drawing d;
  for (int i = 0; i < n; ++i) {
    Curve c;
    const Point2 a((i % 60) * 3.0, (i / 60) * 3.0);
    c.set_spline(line_spline(a, a + Point2(2, 1)));
    d.curves.push_back(c);
  }
  return plan_job(std::move(d), PlanOptions());
}

// Pieces in order, each starting where the one before ended (to the last bit but for the
// sum's own rounding: a piece's length is taken between its rounded ends).
void expect_contiguous(const nlohmann::json& path) {
  double at_mm = 0;
  for (const nlohmann::json& p : path["pieces"]) {
    EXPECT_NEAR(p["start_mm"].get<double>(), at_mm, 1e-9);
    EXPECT_GE(p["points_mm"].size(), 1u);
    at_mm = p["start_mm"].get<double>() + p["length_mm"].get<double>();
  }
  EXPECT_NEAR(at_mm, path["length_mm"].get<double>(), 1e-9);
}

size_t points_in(const nlohmann::json& path) {
  size_t n = 0;
  for (const nlohmann::json& p : path["pieces"]) n += p["points_mm"].size();
  return n;
}

// A page cannot draw three million pieces, nor the server hold them as JSON (2.2 GB for a
// million lines): past its budget the preview is thinned, its lengths still exact.
TEST(JobPath, ALargeJobsPreviewIsThinnedToItsBudgetWithExactLengths) {
  const JobPlan plan = separate_lines(3000);
  const JobPath path(plan);
  const nlohmann::json exact = path.to_json();
  EXPECT_EQ(exact["thinned_to_mm"].get<double>(), 0.0);
  EXPECT_GE(exact["pieces"].size(), 2u * 3000);  // the travel to it and the cut
  expect_contiguous(exact);
  const nlohmann::json thin = path.to_json(2000);
  EXPECT_GT(thin["thinned_to_mm"].get<double>(), 0.0);
  EXPECT_LE(points_in(thin), 2000u);
  EXPECT_GT(points_in(thin), 100u);  // thinned only as far as it had to be
  EXPECT_EQ(thin["length_mm"], exact["length_mm"]);
  expect_contiguous(thin);
}

// Two points (8 bytes each) and two pieces (12 each) a line, its four steps' piece a bit
// each: ~41 bytes, where double points, 16-byte pieces and a piece per step took ~80, and a
// piece with two vectors of its own ~300.
TEST(JobPath, ALineTakesAboutFortyBytes) {
  const int n = 3000;
  const JobPlan plan = separate_lines(n);
  const JobPath path(plan);
  const double per_line = static_cast<double>(path.heap_bytes()) / n;
  RecordProperty("job_path_bytes_a_line", std::to_string(per_line));
  EXPECT_LT(per_line, 45);
}

// Each step's piece, as the walk over the plan gives it, far into a job whose curves are
// sent as several splines (the index is kept 64 steps a word).
TEST(JobPath, EveryStepFindsItsPieceAcrossTheIndexsWords) {
  Drawing d;
  for (int i = 0; i < 48; ++i) {  // wavy lines of 48 arcs: several spline steps each
    std::vector<BulgeVertex> wave;
    for (int k = 0; k <= 48; ++k) wave.push_back({Point2(k * 2.0, 5 + i * 2.5), 0.3});
    Curve c;
    c.set_spline(polyline_spline(wave, false));
    d.curves.push_back(c);
  }
  const JobPlan plan = plan_job(std::move(d), PlanOptions());
  ASSERT_GT(plan.steps.size(), 3u * 64) << plan.steps.size();  // four words
  std::vector<size_t> expected;  // the first piece at or after each step
  size_t pieces = 0;
  bool continued = false;
  walk_tool_path(plan, 0.02, [&](const ToolMove& m) {
    continued = continued || m.kind == StepMove::kContinues;
    expected.push_back(m.kind == StepMove::kContinues ? pieces - 1 : pieces);
    if (m.kind == StepMove::kNew) ++pieces;
  });
  ASSERT_TRUE(continued);
  const JobPath path(plan);
  ASSERT_EQ(path.to_json()["pieces"].size(), pieces);
  for (size_t s = 0; s < plan.steps.size(); ++s) {
    EXPECT_EQ(path.piece_of_step(s), expected[s]) << "step " << s;
  }
}

}  // namespace
}  // namespace host::server
