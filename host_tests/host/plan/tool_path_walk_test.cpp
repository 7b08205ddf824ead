// The one walker of a plan's tool path (the plot's planned path and the server's live preview
// both use it): what each step moves, with which pen, and a curve sent in pieces as one move.
#include <gtest/gtest.h>

#include <vector>  // std::vector

#include "host/lib/drawing/conics.h"  // line_spline
#include "host/lib/plan/tool_path_walk.h"

namespace host {
namespace {

PlanStep step(PlanStep::Kind kind, int32_t x_um = 0, int32_t y_um = 0, int curve = -1) {
  PlanStep s;
  s.kind = kind;
  s.to.x_um = x_um;
  s.to.y_um = y_um;
  s.curve = curve;
  return s;
}

// A 10 mm line from (5, 5) mm as a degree-1 curve.
PlannedCurve line_from_5_5() {
  PlannedCurve c;
  c.set_spline(line_spline(Point2(5, 5), Point2(15, 5)));
  return c;
}

// pen up, rapid, pen down, the line sent as two spline steps, a feed, pen up, dwell, drill.
JobPlan small_plan() {
  JobPlan plan;
  plan.curves.push_back(line_from_5_5());
  plan.steps = {step(PlanStep::kPenUp),
                step(PlanStep::kRapid, 5000, 5000),
                step(PlanStep::kPenDown),
                step(PlanStep::kSpline, 10000, 5000, 0),
                step(PlanStep::kSpline, 15000, 5000, 0),
                step(PlanStep::kFeed, 15000, 8000),
                step(PlanStep::kPenUp),
                step(PlanStep::kDwell),
                step(PlanStep::kDrill, 20000, 20000)};
  return plan;
}

TEST(ToolPathWalk, VisitsEveryStepWithWhatItMovesAndThePenItMovesWith) {
  std::vector<ToolMove> moves;
  walk_tool_path(small_plan(), 0.01, [&moves](const ToolMove& m) { moves.push_back(m); });
  ASSERT_EQ(moves.size(), 9u);
  const std::vector<StepMove> kinds = {StepMove::kNone, StepMove::kNew,       StepMove::kNone,
                                       StepMove::kNew,  StepMove::kContinues, StepMove::kNew,
                                       StepMove::kNone, StepMove::kNone,      StepMove::kNew};
  const std::vector<bool> pen = {false, false, true, true, true, true, false, false, false};
  for (size_t i = 0; i < moves.size(); ++i) {
    EXPECT_EQ(moves[i].step, i);
    EXPECT_EQ(moves[i].kind, kinds[i]) << "step " << i;
    EXPECT_EQ(moves[i].pen_down, pen[i]) << "step " << i;
  }
  // The rapid and the drill go to their ends; the curve is its samples, once.
  ASSERT_EQ(moves[1].points_mm.size(), 1u);
  EXPECT_EQ(moves[1].points_mm[0], Point2(5, 5));
  EXPECT_GE(moves[3].points_mm.size(), 2u);
  EXPECT_EQ(moves[3].points_mm.front(), Point2(5, 5));
  EXPECT_EQ(moves[3].points_mm.back(), Point2(15, 5));
  EXPECT_TRUE(moves[4].points_mm.empty());
  EXPECT_EQ(moves[5].points_mm, std::vector<Point2>{Point2(15, 8)});
  EXPECT_EQ(moves[8].points_mm, std::vector<Point2>{Point2(20, 20)});
}

TEST(ToolPathWalk, TheSameCurveAfterAnotherStepIsANewMove) {
  JobPlan plan = small_plan();
  plan.steps.push_back(step(PlanStep::kSpline, 15000, 5000, 0));  // after the drill
  std::vector<StepMove> kinds;
  walk_tool_path(plan, 0.01, [&kinds](const ToolMove& m) { kinds.push_back(m.kind); });
  EXPECT_EQ(kinds.back(), StepMove::kNew);
}

}  // namespace
}  // namespace host
