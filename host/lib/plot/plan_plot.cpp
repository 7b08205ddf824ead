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
    in.drawing_curves_mm.push_back(straight ? s.control : sample(s, tol_mm));
  }
  if (!with_planned_path) return in;
  Point2 at(0, 0);
  // A move starts where the last one ended: with a new pen state, from there.
  walk_tool_path(plan, tol_mm, [&](const ToolMove& m) {
    for (const Point2& p : m.points_mm) {
      const size_t n = in.tool_path.size();
      if (n == 0 || in.tool_path.pen_down(n - 1) != m.pen_down) in.tool_path.add(at, m.pen_down);
      in.tool_path.add(p, m.pen_down);
      at = p;
    }
  });
  return in;
}

}  // namespace host
