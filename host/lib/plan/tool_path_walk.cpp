// The tool's path through a plan's steps (see tool_path_walk.h).
#include "host/lib/plan/tool_path_walk.h"

namespace host {

namespace {

Point2 mm(const core::PointUm& p) {
  return Point2(p.x_um / 1000.0, p.y_um / 1000.0);
}

}  // namespace

void walk_tool_path(const JobPlan& plan, double tol_mm,
                    const std::function<void(const ToolMove&)>& visit) {
  ToolMove m;
  int last_curve = -1;  // the curve the last spline step drew
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    const PlanStep& s = plan.steps[i];
    m.step = i;
    m.kind = StepMove::kNone;
    m.points_mm.clear();
    switch (s.kind) {
      case PlanStep::kPenUp:
        m.pen_down = false;
        break;
      case PlanStep::kPenDown:
        m.pen_down = true;
        break;
      case PlanStep::kRapid:
      case PlanStep::kFeed:
      case PlanStep::kDrill:  // the tool goes to the hole at travel height
        m.kind = StepMove::kNew;
        m.points_mm.push_back(mm(s.to));
        break;
      case PlanStep::kSpline:
        if (s.curve >= 0 && s.curve == last_curve) {
          m.kind = StepMove::kContinues;
        } else if (s.curve >= 0) {
          m.kind = StepMove::kNew;
          m.points_mm = sample(plan.curves[s.curve].spline(), tol_mm);
        } else {
          m.kind = StepMove::kNew;
          m.points_mm.push_back(mm(s.to));
        }
        break;
      case PlanStep::kPause:
      case PlanStep::kDwell:
      case PlanStep::kSpindle:
        break;
    }
    last_curve = s.kind == PlanStep::kSpline ? s.curve : -1;
    visit(m);
  }
}

}  // namespace host
