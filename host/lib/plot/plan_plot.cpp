// Builds a PlotInput from a JobPlan (see plan_plot.h).
#include "host/lib/plot/plan_plot.h"

namespace host {

namespace {

Point2 mm(const core::PointUm& p) {
  return Point2(p.x_um / 1000.0, p.y_um / 1000.0);
}

}  // namespace

PlotInput plot_input_from_plan(const JobPlan& plan, const std::string& title, double tol_mm,
                               bool with_planned_path) {
  PlotInput in;
  in.title = title;
  in.drawing_curves_mm.reserve(plan.curves.size());
  for (const PlannedCurve& c : plan.curves) {
    const bool straight = c.spline.degree == 1 && c.spline.weights.empty();
    in.drawing_curves_mm.push_back(straight ? c.spline.control : sample(c.spline, tol_mm));
  }
  if (!with_planned_path) return in;
  Point2 at(0, 0);
  bool down = false;
  int last_curve = -1;
  // Appends a point to the current segment, starting a new one when the pen state changes.
  auto add = [&](const Point2& p) {
    if (in.tool_path.empty() || in.tool_path.back().pen_down != down) {
      ToolPathSegment s;
      s.pen_down = down;
      s.points_mm.push_back(at);
      in.tool_path.push_back(s);
    }
    in.tool_path.back().points_mm.push_back(p);
    at = p;
  };
  for (const PlanStep& s : plan.steps) {
    switch (s.kind) {
      case PlanStep::kPenUp:
        down = false;
        break;
      case PlanStep::kPenDown:
        down = true;
        break;
      case PlanStep::kRapid:
      case PlanStep::kFeed:
        add(mm(s.to));
        break;
      case PlanStep::kSpline:
        if (s.curve != last_curve && s.curve >= 0) {
          for (const Point2& p : sample(plan.curves[s.curve].spline, tol_mm)) add(p);
          last_curve = s.curve;
        }
        break;
      case PlanStep::kDrill:  // the hole is at `to`; the tool goes there at travel height
        add(mm(s.to));
        break;
      case PlanStep::kPause:
      case PlanStep::kDwell:
      case PlanStep::kSpindle:
        break;
    }
  }
  return in;
}

}  // namespace host
