// Job planning: lower-left zero, nearest-neighbour ordering with reversal, chaining,
// pen lifts, work-area refusal, firmware form of the curves.
#include "host/lib/plan/job_plan.h"

#include <gtest/gtest.h>

#include <optional>  // std::optional

#include "host/lib/drawing/conics.h"
#include "host/lib/plan/firmware_spline.h"

namespace host {
namespace {

Drawing drawing_of(const std::vector<BSpline>& curves) {
  Drawing d;
  d.path = "test.dxf";
  for (size_t i = 0; i < curves.size(); ++i) {
    Curve c;
    c.set_spline(curves[i]);
    c.kind = "TEST";
    c.source = "TEST #" + std::to_string(i + 1);
    d.curves.push_back(c);
  }
  return d;
}

int count(const JobPlan& p, PlanStep::Kind k) {
  int n = 0;
  for (const PlanStep& s : p.steps) n += s.kind == k ? 1 : 0;
  return n;
}

TEST(JobPlan, LowerLeftCornerOfTheExtentsBecomesTheZero) {
  const JobPlan p =
      plan_job(drawing_of({arc_spline({-20, 30}, 5, 0, 6.283185307179586)}), PlanOptions());
  EXPECT_NEAR(p.offset_mm.x(), 25.0, 1e-6);
  EXPECT_NEAR(p.offset_mm.y(), -25.0, 1e-6);
  EXPECT_NEAR(p.extents_mm.min.x(), 0.0, 1e-6);
  EXPECT_NEAR(p.extents_mm.max.y(), 10.0, 1e-6);
}

TEST(JobPlan, NearestNeighbourOrderReversesCurvesToShortenRapids) {
  // Three separate segments; from the zero the nearest end is the far end of curve 1.
  const Drawing d = drawing_of(
      {line_spline({50, 0}, {60, 0}), line_spline({10, 0}, {0, 0}), line_spline({30, 0}, {20, 0})});
  const JobPlan p = plan_job(d, PlanOptions());
  ASSERT_EQ(p.curves.size(), 3u);
  EXPECT_EQ(p.curves[0].drawing_index, 1);
  EXPECT_TRUE(p.curves[0].reversed);
  EXPECT_EQ(p.curves[1].drawing_index, 2);
  EXPECT_TRUE(p.curves[1].reversed);
  EXPECT_EQ(p.curves[2].drawing_index, 0);
  EXPECT_FALSE(p.curves[2].reversed);
  EXPECT_NEAR(p.rapid_length_mm, 0 + 10 + 20 + 60, 1e-6);  // out, two gaps, home
}

TEST(JobPlan, DrawingOrderIsKeptWithoutReorder) {
  PlanOptions o;
  o.reorder = false;
  const Drawing d = drawing_of({line_spline({50, 0}, {60, 0}), line_spline({10, 0}, {0, 0})});
  const JobPlan p = plan_job(d, o);
  EXPECT_EQ(p.curves[0].drawing_index, 0);
  EXPECT_EQ(p.curves[1].drawing_index, 1);
}

TEST(JobPlan, CurvesMeetingWithinTheToleranceAreChainedWithoutPenLift) {
  // A square from four lines, the third starting 5 um off: chained, with a short feed.
  const Drawing d = drawing_of({line_spline({0, 0}, {10, 0}), line_spline({10, 0}, {10, 10}),
                                line_spline({10.005, 10}, {0, 10}), line_spline({0, 10}, {0, 0})});
  const JobPlan p = plan_job(d, PlanOptions());
  EXPECT_EQ(p.pen_lifts, 0);
  EXPECT_EQ(count(p, PlanStep::kPenDown), 1);
  EXPECT_TRUE(p.curves[1].chained);
  EXPECT_TRUE(p.curves[2].chained);
  EXPECT_EQ(count(p, PlanStep::kFeed), 4 + 1);  // four lines + the 5 um gap
}

TEST(JobPlan, CurvesFartherApartThanTheToleranceLiftThePen) {
  PlanOptions o;
  o.chain_tolerance_mm = 0.001;
  const Drawing d = drawing_of({line_spline({0, 0}, {10, 0}), line_spline({10.005, 0}, {20, 0})});
  const JobPlan p = plan_job(d, o);
  EXPECT_EQ(p.pen_lifts, 1);
  EXPECT_EQ(count(p, PlanStep::kPenDown), 2);
}

TEST(JobPlan, StepsStartAndEndPenUpAtTheZero) {
  const JobPlan p = plan_job(drawing_of({line_spline({5, 5}, {6, 6})}), PlanOptions());
  ASSERT_GE(p.steps.size(), 4u);
  EXPECT_EQ(p.steps.front().kind, PlanStep::kPenUp);
  EXPECT_EQ(p.steps.front().z_um, 2000);
  EXPECT_EQ(p.steps.back().kind, PlanStep::kRapid);
  EXPECT_EQ(p.steps.back().to.x_um, 0);
  EXPECT_EQ(p.steps[p.steps.size() - 2].kind, PlanStep::kPenUp);
}

TEST(JobPlan, SplineStepsCarryValidFirmwareSplinesStartingAtTheRapidTarget) {
  const JobPlan p = plan_job(drawing_of({arc_spline({0, 0}, 10, 0, 3.0)}), PlanOptions());
  std::optional<PlanStep> rapid;
  int splines = 0;
  for (const PlanStep& s : p.steps) {
    if (s.kind == PlanStep::kRapid && !rapid) rapid = s;
    if (s.kind == PlanStep::kSpline) {
      ++splines;
      EXPECT_EQ(core::validate_spline(s.spline().firmware()), core::GeometryError::kOk);
      EXPECT_EQ(s.feed_um_per_s, 10000);
      const Point2 start = start_point(from_firmware_spline(s.spline().firmware()));
      ASSERT_TRUE(rapid.has_value());
      EXPECT_NEAR(start.x() * 1000, rapid->to.x_um, 1.0);
      EXPECT_NEAR(start.y() * 1000, rapid->to.y_um, 1.0);
    }
  }
  EXPECT_EQ(splines, 1);
}

TEST(JobPlan, ToolOffsetSignFollowsTheDrawnDirectionWhenReversed) {
  PlanOptions o;
  o.tool_side = ToolSide::kLeft;
  o.tool_radius_mm = 0.1;
  o.margin_mm = 1.0;
  // Drawn from far to near: the planner reverses it, so "left as drawn" is right of travel.
  const JobPlan p = plan_job(drawing_of({line_spline({30, 0}, {0, 0})}), o);
  ASSERT_TRUE(p.curves[0].reversed);
  for (const PlanStep& s : p.steps) {
    if (s.kind == PlanStep::kSpline) EXPECT_EQ(s.tool_offset_um, -100);
  }
}

TEST(JobPlan, OutOfWorkAreaIsRefusedNamingTheCurveAndTheCoordinate) {
  PlanOptions o;  // A4: 297 x 210
  const Drawing d = drawing_of({line_spline({0, 0}, {100, 0}), line_spline({0, 0}, {0, 250})});
  try {
    plan_job(d, o);
    FAIL() << "accepted";
  } catch (const PlanError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("curve 1 (TEST #2)"), std::string::npos) << m;
    EXPECT_NE(m.find("(0, 250) mm"), std::string::npos) << m;
  }
}

TEST(JobPlan, ToolRadiusCountsAgainstTheWorkArea) {
  PlanOptions o;
  o.work_width_mm = 100;
  o.work_height_mm = 100;
  o.tool_side = ToolSide::kRight;
  o.tool_radius_mm = 0.5;
  o.margin_mm = 1.0;
  EXPECT_NO_THROW(plan_job(drawing_of({line_spline({0, 0}, {98, 0})}), o));
  EXPECT_THROW(plan_job(drawing_of({line_spline({0, 0}, {98.6, 0})}), o), PlanError);
}

TEST(JobPlan, ScaleAppliesBeforeTheWorkAreaCheck) {
  PlanOptions o;
  o.scale = 2.0;
  const JobPlan p = plan_job(drawing_of({line_spline({0, 0}, {100, 0})}), o);
  EXPECT_NEAR(p.extents_mm.width(), 200.0, 1e-6);
  o.scale = 3.0;
  EXPECT_THROW(plan_job(drawing_of({line_spline({0, 0}, {100, 0})}), o), PlanError);
}

TEST(JobPlan, EmptyDrawingIsRefused) {
  EXPECT_THROW(plan_job(Drawing(), PlanOptions()), PlanError);
}

}  // namespace
}  // namespace host
