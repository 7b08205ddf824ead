// The memory a plan takes per step: a step keeps its spline out of line (only the control
// points and knots used), so steps without a curve carry no firmware spline. An inline
// core::Spline (about 1.1 kB) in every step made a million-segment job take gigabytes.
#include <gtest/gtest.h>

#include <cmath>  // std::signbit

#include "host/lib/drawing/conics.h"
#include "host/lib/plan/firmware_spline.h"
#include "host/lib/plan/job_plan.h"

namespace host {
namespace {

Drawing separate_lines(int n) {
  Drawing d;
  d.path = "lines.dxf";
  for (int i = 0; i < n; ++i) {
    Curve c;
    const double x = (i % 50) * 4.0, y = (i / 50) * 4.0;
    c.set_spline(line_spline({x, y}, {x + 1.5, y + 0.5}));
    c.kind = "LINE";
    c.source = "LINE #" + std::to_string(i + 1);
    d.curves.push_back(c);
  }
  return d;
}

TEST(PlanStepMemory, AStepIsFarSmallerThanAFirmwareSpline) {
  // Fails if a core::Spline (or anything of its size) goes back into PlanStep, or the
  // spline's vectors and the pause text sit in every step again (128 bytes then).
  EXPECT_LT(sizeof(PlanStep), sizeof(core::Spline) / 4);
  EXPECT_LE(sizeof(PlanStep), 64u);
}

TEST(PlanStepMemory, AStepIsFortyBytes) {
  // A million-line job holds four million steps: 56 bytes each (a 4-byte kind, the dwell
  // and the drill start apart, a two-word shared_ptr) were 224 MB, 40 bytes are 160 MB.
  EXPECT_LE(sizeof(PlanStep), 40u);
}

TEST(PlanStepMemory, TheDwellAndTheDrillStartKeepTheirValuesOnTheirKinds) {
  PlanStep dwell;
  dwell.kind = PlanStep::kDwell;
  dwell.dwell_ms = 1500;
  PlanStep drill;
  drill.kind = PlanStep::kDrill;
  drill.z_start_um = -200;
  drill.z_um = -1800;
  const PlanStep dwell_copy = dwell, drill_copy = drill;
  EXPECT_EQ(dwell_copy.dwell_ms, 1500u);
  EXPECT_EQ(drill_copy.z_start_um, -200);
  EXPECT_EQ(drill_copy.z_um, -1800);
  EXPECT_EQ(PlanStep().dwell_ms, 0u);
}

TEST(PlanStepMemory, TheLastCopyOfAStepLetsItsSplineGo) {
  const core::Spline line = to_firmware_splines(line_spline({1, 2}, {3, 4})).front();
  std::vector<PlanStep> steps(1);
  steps[0].set_spline(StepSpline(line));
  const StepSpline* shared = &steps[0].spline();
  steps.resize(1000, steps[0]);  // copies share, moves keep it while the vector grows
  for (const PlanStep& s : steps) ASSERT_EQ(&s.spline(), shared);
  steps.erase(steps.begin(), steps.begin() + 999);
  EXPECT_EQ(&steps[0].spline(), shared);
  EXPECT_EQ(steps[0].spline().control.size(), 2u);
}

TEST(PlanStepMemory, ASplineAndATextAreKeptTogetherAndCopiesShareThem) {
  PlanStep s;
  EXPECT_TRUE(s.spline().empty());
  EXPECT_TRUE(s.text().empty());
  const core::Spline line = to_firmware_splines(line_spline({1, 2}, {3, 4})).front();
  s.set_spline(StepSpline(line));
  s.set_text("T1 0.8mm drill");
  EXPECT_EQ(s.spline().control.size(), 2u);  // setting the text kept the spline
  EXPECT_EQ(s.text(), "T1 0.8mm drill");
  PlanStep copy = s;
  EXPECT_EQ(&copy.spline(), &s.spline());  // shared, not copied
  copy.set_text("other");                  // a change makes the copy its own
  EXPECT_EQ(s.text(), "T1 0.8mm drill");
  EXPECT_EQ(copy.text(), "other");
  EXPECT_EQ(copy.spline().control.size(), 2u);
}

TEST(PlanStepMemory, StepsWithoutACurveHoldNoSplineStorage) {
  PlanOptions o;
  o.lines_as_feeds = true;
  const JobPlan p = plan_job(separate_lines(500), o);
  ASSERT_GT(p.steps.size(), 2000u);  // per line: rapid, plunge, feed, lift
  for (const PlanStep& s : p.steps) {
    ASSERT_NE(s.kind, PlanStep::kSpline);
    EXPECT_TRUE(s.spline().empty());
    EXPECT_EQ(s.spline().control.capacity(), 0u);
    EXPECT_EQ(s.spline().knot.capacity(), 0u);
  }
  // Reserved once from a close bound: no over-reserve (4 + control points per curve once
  // made the vector several times larger than the job), no doubling (1.5x at the peak).
  EXPECT_LE(p.steps.capacity(), p.steps.size() + p.steps.size() / 10);
}

TEST(PlanStepMemory, AChainedPolylineIsReservedForExactlyItsSteps) {
  Drawing d;
  d.path = "chain.dxf";
  for (int i = 0; i < 3000; ++i) {
    Curve c;
    c.set_spline(line_spline({i * 0.05, 0.0}, {(i + 1) * 0.05, 0.0}));
    c.kind = "LINE";
    c.source = "LINE #" + std::to_string(i + 1);
    d.curves.push_back(c);
  }
  PlanOptions o;
  o.lines_as_feeds = true;
  const JobPlan p = plan_job(std::move(d), o);
  ASSERT_GT(p.steps.size(), 3000u);
  EXPECT_LE(p.steps.capacity(), p.steps.size() + p.steps.size() / 10);
}

TEST(PlanStepMemory, SplineStepsHoldOnlyTheControlPointsAndKnotsTheyUse) {
  PlanOptions o;
  o.lines_as_feeds = false;
  const JobPlan p = plan_job(separate_lines(3), o);
  int splines = 0;
  for (const PlanStep& s : p.steps) {
    if (s.kind != PlanStep::kSpline) continue;
    ++splines;
    EXPECT_EQ(s.spline().control.size(), 2u);
    EXPECT_EQ(s.spline().knot.size(), 4u);
    EXPECT_EQ(core::validate_spline(s.spline().firmware()), core::GeometryError::kOk);
  }
  EXPECT_EQ(splines, 3);
}

// A straight line is kept as its two ends and made again bit for bit, its reversal too
// (knots -1 -1 -0 -0); any other curve is kept whole.
TEST(PlannedCurveMemory, AStraightLineComesBackBitForBitEitherWayRound) {
  const BSpline forward = line_spline({1.25, 2.5}, {3.75, -4.125});
  for (const BSpline& want : {forward, reversed(forward)}) {
    PlannedCurve c;
    c.set_spline(want);
    EXPECT_TRUE(c.inline_line());
    const BSpline got = c.spline();
    EXPECT_EQ(got.degree, 1);
    EXPECT_EQ(got.control, want.control);
    EXPECT_TRUE(got.weights.empty());
    ASSERT_EQ(got.knots.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(got.knots[i], want.knots[i]);
      EXPECT_EQ(std::signbit(got.knots[i]), std::signbit(want.knots[i])) << i;
    }
  }
}

TEST(PlannedCurveMemory, OtherCurvesAreKeptWhole) {
  BSpline odd_knots = line_spline({0, 0}, {1, 1});
  odd_knots.knots = {0, 0, 2, 2};
  BSpline three_points = line_spline({0, 0}, {1, 1});
  three_points.control.push_back(Point2(2, 0));
  three_points.knots = {0, 0, 1, 2, 2};
  BSpline weighted = line_spline({0, 0}, {1, 1});
  weighted.weights = {1.0, 1.0};
  for (const BSpline& want :
       {odd_knots, three_points, weighted, arc_spline({20, 20}, 10, 0.3, 5.0)}) {
    PlannedCurve c;
    c.set_spline(want);
    EXPECT_FALSE(c.inline_line());
    const BSpline got = c.spline();
    EXPECT_EQ(got.degree, want.degree);
    EXPECT_EQ(got.control, want.control);
    EXPECT_EQ(got.weights, want.weights);
    EXPECT_EQ(got.knots, want.knots);
  }
  // A copy shares the curve; setting a line afterwards lets it go.
  PlannedCurve c;
  c.set_spline(three_points);
  PlannedCurve copy = c;
  copy.set_spline(line_spline({5, 5}, {6, 6}));
  EXPECT_EQ(c.spline().control.size(), 3u);
  EXPECT_EQ(copy.spline().control.size(), 2u);
  EXPECT_TRUE(PlannedCurve().spline().control.empty());
}

TEST(PlannedCurveMemory, APlannedCurveIsEightyEightBytes) {
  // A million unconnected lines hold a million of them: 120 bytes (a whole BSpline, three
  // vectors) and ~100 more on the heap before.
  EXPECT_LE(sizeof(PlannedCurve), 88u);
}

TEST(StepSpline, RoundTripsTheFirmwareForm) {
  const std::vector<core::Spline> pieces = to_firmware_splines(arc_spline({20, 20}, 10, 0.3, 5.0));
  ASSERT_FALSE(pieces.empty());
  for (const core::Spline& f : pieces) {
    const StepSpline c(f);
    EXPECT_EQ(c.control.size(), f.control_count);
    EXPECT_EQ(c.knot.size(), f.knot_count);
    const core::Spline back = c.firmware();
    EXPECT_EQ(back.degree, f.degree);
    EXPECT_EQ(back.rational, f.rational);
    ASSERT_EQ(back.control_count, f.control_count);
    ASSERT_EQ(back.knot_count, f.knot_count);
    for (unsigned i = 0; i < f.control_count; ++i) {
      EXPECT_EQ(back.control[i].x_um, f.control[i].x_um);
      EXPECT_EQ(back.control[i].y_um, f.control[i].y_um);
      EXPECT_EQ(back.control[i].weight_q14, f.control[i].weight_q14);
    }
    for (unsigned i = 0; i < f.knot_count; ++i) EXPECT_EQ(back.knot[i], f.knot[i]);
  }
}

}  // namespace
}  // namespace host
