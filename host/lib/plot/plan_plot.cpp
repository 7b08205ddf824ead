// Builds a PlotInput from a JobPlan (see plan_plot.h).
#include "host/lib/plot/plan_plot.h"

#include "host/lib/plan/tool_path_walk.h"

namespace host {

PlotInput plot_input_from_plan(const JobPlan& plan, const std::string& title, double tol_mm,
                               bool with_planned_path) {
  PlotInput in;
  in.title = title;
  in.drawing_curves_mm.reserve(plan.curves.size());
  for (const PlannedCurve& c : plan.curves) {
    BSpline s = c.spline();
    const bool straight = s.degree == 1 && s.weights.empty();
    in.drawing_curves_mm.push_back(straight ? std::move(s.control) : sample(s, tol_mm));
  }
  if (!with_planned_path) return in;
  Point2 at(0, 0);
  // Appends the move's points to the current segment, starting a new one when the pen state
  // changes.
  walk_tool_path(plan, tol_mm, [&](const ToolMove& m) {
    for (const Point2& p : m.points_mm) {
      if (in.tool_path.empty() || in.tool_path.back().pen_down != m.pen_down) {
        ToolPathSegment s;
        s.pen_down = m.pen_down;
        s.points_mm.push_back(at);
        in.tool_path.push_back(s);
      }
      in.tool_path.back().points_mm.push_back(p);
      at = p;
    }
  });
  return in;
}

}  // namespace host
