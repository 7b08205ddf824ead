// Job planning: scale, offset to the lower-left zero, nearest-neighbour ordering with
// reversal, chaining of touching curves, work-area check, conversion to firmware splines.
#include "host/lib/plan/job_plan.h"

#include <cmath>    // std::llround, std::isfinite
#include <sstream>  // std::ostringstream

#include "host/lib/plan/firmware_spline.h"
#include "host/lib/plan/nearest_end.h"

namespace host {

namespace {

int32_t to_um(double mm) {
  return static_cast<int32_t>(std::llround(mm * 1000.0));
}

core::PointUm to_um(const Point2& p) {
  core::PointUm q;
  q.x_um = to_um(p.x());
  q.y_um = to_um(p.y());
  return q;
}

// Length of a polyline approximation of the curve.
double curve_length(const BSpline& s) {
  const std::vector<Point2> pts = sample(s, 0.001);
  double len = 0;
  for (size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  return len;
}

// True when the curve is exactly a chain of straight segments through its control points.
bool is_polyline(const BSpline& s) {
  if (s.degree != 1) return false;
  return s.knots[0] == s.knots[1] && s.knots[s.knots.size() - 1] == s.knots[s.knots.size() - 2];
}

// "curve N (entity)" with N the drawing's curve number (as `engraver info` shows it).
std::string describe(const PlannedCurve& c) {
  std::ostringstream o;
  o << "curve " << c.drawing_index << " (" << c.source << ")";
  return o.str();
}

// Refuses a curve that leaves the work area (tool centre, including the tool radius).
void check_work_area(const PlannedCurve& c, double radius, const PlanOptions& o) {
  for (const Point2& p : sample(c.spline, 0.001)) {
    const double lo_x = p.x() - radius, hi_x = p.x() + radius;
    const double lo_y = p.y() - radius, hi_y = p.y() + radius;
    std::ostringstream e;
    if (lo_x < -1e-6 || hi_x > o.work_width_mm + 1e-6 || lo_y < -1e-6 ||
        hi_y > o.work_height_mm + 1e-6) {
      e << describe(c) << " leaves the work area (0..";
      e << o.work_width_mm << " x 0.." << o.work_height_mm << " mm): it reaches (" << p.x() << ", "
        << p.y() << ") mm in the machine frame";
      if (radius > 0) e << " with the tool radius " << radius << " mm";
      e << ". Scale the drawing down (--scale) or use a larger work area (--work W H).";
      throw PlanError(e.str());
    }
  }
}

}  // namespace

JobPlan plan_job(const Drawing& drawing, const PlanOptions& o) {
  if (drawing.curves.empty())
    throw PlanError(drawing.path + ": the drawing has nothing to engrave");
  if (!(o.scale > 0) || !std::isfinite(o.scale)) throw PlanError("scale must be positive");
  if (!(o.feed_mm_per_s > 0) || !(o.plunge_mm_per_s > 0)) throw PlanError("feeds must be positive");
  if (!(o.tool_radius_mm >= 0)) throw PlanError("tool radius must not be negative");
  JobPlan plan;
  // Scale, then put the lower-left corner of the extents at (margin, margin).
  Eigen::Matrix2d scale = Eigen::Matrix2d::Identity() * o.scale;
  std::vector<BSpline> scaled;
  Extents ext;
  for (const Curve& c : drawing.curves) {
    scaled.push_back(transformed(c.spline, scale, Point2(0, 0)));
    ext.add(curve_extents(scaled.back()));
  }
  plan.offset_mm = Point2(o.margin_mm, o.margin_mm) - ext.min;
  for (BSpline& s : scaled) s = transformed(s, Eigen::Matrix2d::Identity(), plan.offset_mm);
  const double radius = o.tool_side == ToolSide::kCentre ? 0.0 : o.tool_radius_mm;

  // Greedy nearest neighbour from the zero, each curve either way round.
  std::vector<Point2> starts, ends;
  for (const BSpline& s : scaled) {
    starts.push_back(start_point(s));
    ends.push_back(end_point(s));
  }
  NearestEnd index(starts, ends);
  Point2 at(0, 0);
  for (size_t n = 0; n < scaled.size(); ++n) {
    if (o.progress && n % 4096 == 0) o.progress(n, scaled.size());
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
    PlannedCurve pc;
    pc.spline = best_rev ? reversed(scaled[best]) : scaled[best];
    pc.drawing_index = static_cast<int>(best);
    pc.reversed = best_rev;
    pc.chained = n > 0 && best_d <= o.chain_tolerance_mm;
    pc.source = drawing.curves[best].source;
    at = best_rev ? starts[best] : ends[best];
    plan.curves.push_back(pc);
  }

  // Work area, before anything else is produced.
  for (size_t i = 0; i < plan.curves.size(); ++i) {
    check_work_area(plan.curves[i], radius, o);
    plan.extents_mm.add(curve_extents(plan.curves[i].spline));
  }

  const int32_t feed = to_um(o.feed_mm_per_s);
  const int32_t plunge = to_um(o.plunge_mm_per_s);
  PlanStep up;
  up.kind = PlanStep::kPenUp;
  up.z_um = to_um(o.z_up_mm);
  plan.steps.push_back(up);
  bool pen_down = false;
  at = Point2(0, 0);
  for (size_t i = 0; i < plan.curves.size(); ++i) {
    const PlannedCurve& c = plan.curves[i];
    const Point2 start = start_point(c.spline);
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
    // Offset sign: left of the curve as drawn; reversed curves swap sides.
    int32_t offset = 0;
    if (o.tool_side != ToolSide::kCentre) {
      offset = to_um(o.tool_radius_mm) * (o.tool_side == ToolSide::kLeft ? 1 : -1);
      if (c.reversed) offset = -offset;
    }
    if (o.lines_as_feeds && offset == 0 && is_polyline(c.spline)) {
      for (size_t k = 1; k < c.spline.control.size(); ++k) {
        PlanStep f;
        f.kind = PlanStep::kFeed;
        f.to = to_um(c.spline.control[k]);
        f.feed_um_per_s = feed;
        f.curve = static_cast<int>(i);
        plan.steps.push_back(f);
      }
    } else {
      std::vector<core::Spline> pieces;
      try {
        pieces = to_firmware_splines(c.spline);
      } catch (const ConversionError& e) {
        throw PlanError(describe(c) + ": " + e.what());
      }
      for (size_t k = 0; k < pieces.size(); ++k) {
        PlanStep s;
        s.kind = PlanStep::kSpline;
        s.spline = pieces[k];
        s.to = to_um(k + 1 == pieces.size() ? end_point(c.spline)
                                            : end_point(from_firmware_spline(pieces[k])));
        s.feed_um_per_s = feed;
        s.tool_offset_um = offset;
        s.curve = static_cast<int>(i);
        plan.steps.push_back(s);
      }
    }
    plan.cut_length_mm += curve_length(c.spline);
    at = end_point(c.spline);
  }
  up.curve = -1;
  plan.steps.push_back(up);
  PlanStep home;
  home.kind = PlanStep::kRapid;
  plan.steps.push_back(home);
  plan.rapid_length_mm += at.norm();
  return plan;
}

}  // namespace host
