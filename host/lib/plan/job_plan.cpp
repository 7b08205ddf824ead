// Job planning: scale, offset to the lower-left zero, nearest-neighbour ordering with
// reversal, chaining of touching curves, work-area check, conversion to firmware splines.
#include "host/lib/plan/job_plan.h"

#include <cmath>        // std::llround, std::isfinite
#include <sstream>      // std::ostringstream
#include <type_traits>  // std::is_const_v
#include <utility>      // std::move

#include "host/lib/plan/nearest_end.h"
#include "host/lib/plan/plan_steps.h"

namespace host {

using namespace plan_detail;

// Defined in program_plan.cpp: the planner for programs (G-code), which keeps their order.
JobPlan plan_program(const Drawing& drawing, const PlanOptions& options);

namespace {

// One curve of the greedy order: which scaled curve, which way round, and whether it
// continues the previous one.
struct OrderedCurve {
  uint32_t index;
  bool reversed;
  bool chained;
};

// Progress (PlanOptions::progress) every 4096 curves of a stage.
void report(const PlanOptions& o, const char* unit, size_t done, size_t total) {
  if (o.progress && done % 4096 == 0) o.progress(unit, done, total);
}

// Greedy nearest neighbour from the zero, each curve either way round. Only the curves' ends
// and the search's index are held here, and they die on return, before the planned curves
// are made: a million-line drawing held them (~120 MB) beside the planned curves.
std::vector<OrderedCurve> greedy_order(const std::vector<Curve>& scaled, const PlanOptions& o) {
  std::vector<Point2> starts, ends;
  starts.reserve(scaled.size());
  ends.reserve(scaled.size());
  for (const Curve& c : scaled) {
    report(o, "curve ends indexed", starts.size(), scaled.size());
    const BSpline s = c.spline();
    starts.push_back(start_point(s));
    ends.push_back(end_point(s));
  }
  NearestEnd index(starts, ends);
  std::vector<OrderedCurve> order;
  order.reserve(scaled.size());
  Point2 at(0, 0);
  for (size_t n = 0; n < scaled.size(); ++n) {
    report(o, "curves ordered", n, scaled.size());
    size_t best = n;
    bool best_rev = false;
    double best_d = (starts[n] - at).norm();
    if (o.reorder) {
      const NearestEnd::Hit hit = index.nearest(at);
      best = hit.index;
      best_rev = hit.reversed;
      best_d = hit.distance;
    }
    index.use(best);
    order.push_back(OrderedCurve{static_cast<uint32_t>(best), best_rev,
                                 n > 0 && best_d <= o.chain_tolerance_mm});
    at = best_rev ? starts[best] : ends[best];
  }
  return order;
}

// The scaled curves into plan->curves in the greedy order, each curve and name moved (a copy
// held the drawing twice more). The curves die on return.
void order_curves(std::vector<Curve> scaled, const PlanOptions& o, JobPlan* plan) {
  const std::vector<OrderedCurve> order = greedy_order(scaled, o);
  plan->curves.reserve(scaled.size());  // one each; growing by doubling held 1.5x of them
  for (const OrderedCurve& k : order) {
    Curve& c = scaled[k.index];
    PlannedCurve pc;
    BSpline s = c.spline();
    pc.set_spline(k.reversed ? reversed(s) : std::move(s));
    c.held = HeldSpline();
    pc.drawing_index = static_cast<int>(k.index);
    pc.reversed = k.reversed;
    pc.chained = k.chained;
    pc.source = std::move(c.source);
    plan->curves.push_back(std::move(pc));
  }
}

// Plans the curves of a drawing without a program, already scaled (drawing frame, mm).
JobPlan plan_scaled(std::vector<Curve> scaled, const PlanOptions& o) {
  JobPlan plan;
  // Put the lower-left corner of the extents at (margin, margin).
  Extents ext;
  for (size_t i = 0; i < scaled.size(); ++i) {
    report(o, "curves measured", i, scaled.size());
    ext.add(curve_extents(scaled[i].spline()));
  }
  plan.offset_mm =
      o.fixed_offset ? o.offset_mm : Point2(Point2(o.margin_mm, o.margin_mm) - ext.min);
  for (size_t i = 0; i < scaled.size(); ++i) {
    report(o, "curves moved to the margin", i, scaled.size());
    scaled[i].set_spline(
        transformed(scaled[i].spline(), Eigen::Matrix2d::Identity(), plan.offset_mm));
  }
  const double radius = o.tool_side == ToolSide::kCentre ? 0.0 : o.tool_radius_mm;
  order_curves(std::move(scaled), o, &plan);

  // Work area, before anything else is produced.
  std::string culprit;
  for (size_t i = 0; i < plan.curves.size(); ++i) {
    report(o, "curves checked against the work area", i, plan.curves.size());
    if (culprit.empty()) culprit = first_exit(plan.curves[i], radius, o);
    plan.extents_mm.add(curve_extents(plan.curves[i].spline()));
  }
  check_job_fits(plan.extents_mm, radius, o, culprit);

  const int32_t feed = to_um(o.feed_mm_per_s);
  const int32_t plunge = to_um(o.plunge_mm_per_s);
  // Steps reserved from a close upper bound: growing by doubling held up to 1.5x the steps
  // at the last reallocation (201 instead of 128 MB for a million-line contour). A polyline
  // drawn as feeds is one step per line; a spline a step per firmware piece (64 control
  // points, overlapping by the degree: at most n / 32 + 1); a chained curve a feed across a
  // gap, if any; a separate one its lift, travel and plunge. The loop below makes them.
  auto offset_of = [&](const PlannedCurve& c) -> int32_t {
    if (o.tool_side == ToolSide::kCentre) return 0;
    const int32_t r = to_um(o.tool_radius_mm) * (o.tool_side == ToolSide::kLeft ? 1 : -1);
    return c.reversed ? -r : r;
  };
  {
    size_t bound = 3;
    Point2 end(0, 0);
    for (const PlannedCurve& c : plan.curves) {
      const int32_t offset = offset_of(c);
      const BSpline s = c.spline();
      const size_t n = s.control.size();
      const bool feeds = o.lines_as_feeds && offset == 0 && is_polyline(s);
      bound += feeds ? n - 1 : n / 32 + 1;
      const core::PointUm start = to_um(offset_point(s, true, offset));
      const core::PointUm last = to_um(end);
      bound += !c.chained ? 3 : (start.x_um != last.x_um || start.y_um != last.y_um) ? 1 : 0;
      end = offset_point(s, false, offset);
    }
    plan.steps.reserve(bound);
  }
  PlanStep up;
  up.kind = PlanStep::kPenUp;
  up.z_um = to_um(o.z_up_mm);
  plan.steps.push_back(up);
  bool pen_down = false;
  Point2 at(0, 0);
  for (size_t i = 0; i < plan.curves.size(); ++i) {
    report(o, "curves made into steps", i, plan.curves.size());
    const PlannedCurve& c = plan.curves[i];
    // Offset sign: left of the curve as drawn; reversed curves swap sides.
    const int32_t offset = offset_of(c);
    const BSpline s = c.spline();
    const Point2 start = offset_point(s, true, offset);
    if (!c.chained) {
      if (pen_down) {
        up.curve = static_cast<int>(i);
        plan.steps.push_back(up);
        ++plan.pen_lifts;
      }
      PlanStep r;
      r.kind = PlanStep::kRapid;
      r.to = to_um(start);
      r.curve = static_cast<int>(i);
      plan.steps.push_back(r);
      plan.rapid_length_mm += (start - at).norm();
      PlanStep d;
      d.kind = PlanStep::kPenDown;
      d.z_um = to_um(o.z_down_mm);
      d.feed_um_per_s = plunge;
      d.curve = static_cast<int>(i);
      plan.steps.push_back(d);
      pen_down = true;
    } else if (to_um(start).x_um != to_um(at).x_um || to_um(start).y_um != to_um(at).y_um) {
      // Within the chaining tolerance: close the small gap with a straight feed.
      PlanStep f;
      f.kind = PlanStep::kFeed;
      f.to = to_um(start);
      f.feed_um_per_s = feed;
      f.curve = static_cast<int>(i);
      plan.steps.push_back(f);
    }
    append_curve_steps(c, s, static_cast<int>(i), offset, o, &plan);
    plan.cut_length_mm += curve_length(s);
    at = offset_point(s, false, offset);
  }
  up.curve = -1;
  plan.steps.push_back(up);
  PlanStep home;
  home.kind = PlanStep::kRapid;
  plan.steps.push_back(home);
  plan.rapid_length_mm += at.norm();
  return plan;
}

void check_not_empty(const Drawing& drawing) {
  if (drawing.curves.empty() && drawing.program.empty())
    throw PlanError(drawing.path + ": the drawing has nothing to engrave");
}

// Checks and plans a drawing: a const one is kept (its curves copied: a line's ends, any
// other curve shared); one its caller gives up (Drawing&) has its curves planned in place,
// so a large drawing is held once, not twice, while planning.
template <class D>
JobPlan plan_drawing(D& drawing, const PlanOptions& o) {
  constexpr bool give_up = !std::is_const_v<D>;
  check_not_empty(drawing);
  check_options(o);
  if (!drawing.program.empty()) return plan_program(drawing, o);
  std::vector<Curve> scaled;
  if constexpr (give_up) {
    scaled = std::move(drawing.curves);
    std::vector<Curve>().swap(drawing.curves);
  } else {
    scaled = drawing.curves;
  }
  if (o.scale != 1.0) {
    const Eigen::Matrix2d scale = Eigen::Matrix2d::Identity() * o.scale;
    for (Curve& c : scaled) c.set_spline(transformed(c.spline(), scale, Point2(0, 0)));
  }
  return plan_scaled(std::move(scaled), o);
}

}  // namespace

JobPlan plan_job(const Drawing& drawing, const PlanOptions& o) {
  return plan_drawing(drawing, o);
}

JobPlan plan_job(Drawing&& drawing, const PlanOptions& o) {
  return plan_drawing(drawing, o);
}

}  // namespace host
