// Shared planner pieces; see plan_steps.h.
#include "host/lib/plan/plan_steps.h"

#include <algorithm>  // std::min, std::none_of
#include <cmath>      // std::llround, std::floor
#include <sstream>    // std::ostringstream

#include "host/lib/plan/firmware_spline.h"

namespace host {

namespace plan_detail {

namespace {

// A size for a message: at most 3 decimals, no trailing zeros.
std::string mm(double v) {
  std::ostringstream o;
  o << std::llround(v * 1000) / 1000.0;
  return o.str();
}

}  // namespace

bool is_polyline(const BSpline& s) {
  if (s.degree != 1) return false;
  return s.knots[0] == s.knots[1] && s.knots[s.knots.size() - 1] == s.knots[s.knots.size() - 2];
}

int32_t to_um(double mm) {
  return static_cast<int32_t>(std::llround(mm * 1000.0));
}

core::PointUm to_um(const Point2& p) {
  core::PointUm q;
  q.x_um = to_um(p.x());
  q.y_um = to_um(p.y());
  return q;
}

double curve_length(const BSpline& s) {
  const std::vector<Point2> pts = sample(s, 0.001);
  double len = 0;
  for (size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  return len;
}

std::string describe(const PlannedCurve& c) {
  std::ostringstream o;
  o << "curve " << c.drawing_index << " (" << c.source << ")";
  return o.str();
}

std::string first_exit(const PlannedCurve& c, double radius, const PlanOptions& o) {
  auto outside = [&](const Point2& p) {
    return p.x() - radius < -1e-6 || p.x() + radius > o.work_width_mm + 1e-6 ||
           p.y() - radius < -1e-6 || p.y() + radius > o.work_height_mm + 1e-6;
  };
  // A B-spline lies in its control points' convex hull: with every control point inside, so
  // is the curve, and sampling it at 1 um (most of planning's time for a job of many short
  // lines) finds nothing.
  const BSpline s = c.spline();
  if (std::none_of(s.control.begin(), s.control.end(), outside)) return "";
  for (const Point2& p : sample(s, 0.001)) {
    if (outside(p)) {
      std::ostringstream e;
      e << describe(c) << " reaches (" << p.x() << ", " << p.y() << ") mm in the machine frame";
      return e.str();
    }
  }
  return "";
}

void check_job_fits(const Extents& ext, double radius, const PlanOptions& o,
                    const std::string& culprit) {
  if (ext.empty()) return;
  const double lo_x = ext.min.x() - radius, hi_x = ext.max.x() + radius;
  const double lo_y = ext.min.y() - radius, hi_y = ext.max.y() + radius;
  if (lo_x >= -1e-6 && lo_y >= -1e-6 && hi_x <= o.work_width_mm + 1e-6 &&
      hi_y <= o.work_height_mm + 1e-6) {
    return;
  }
  const double w = ext.width(), h = ext.height();
  std::ostringstream e;
  e << "the job does not fit the work area: the drawing is " << mm(w) << " x " << mm(h)
    << " mm at --scale " << o.scale;
  if (radius > 0) e << ", plus the tool radius " << mm(radius) << " mm on every side";
  if (o.fixed_offset) {
    e << "; placed at --offset " << mm(o.offset_mm.x()) << " " << mm(o.offset_mm.y())
      << " mm it spans x ";
  } else {
    e << "; placed with its lower-left corner at --margin " << mm(o.margin_mm)
      << " mm from the zero it spans x ";
  }
  e << mm(lo_x) << " .. " << mm(hi_x) << ", y " << mm(lo_y) << " .. " << mm(hi_y)
    << " mm; the work area is " << mm(o.work_width_mm) << " x " << mm(o.work_height_mm)
    << " mm (--work).";
  // What would fit: a smaller scale, a smaller margin, a larger work area.
  const double room_x = o.work_width_mm - o.margin_mm - radius;
  const double room_y = o.work_height_mm - o.margin_mm - radius;
  double fit = 1e300;
  if (w > 0) fit = std::min(fit, room_x / w);
  if (h > 0) fit = std::min(fit, room_y / h);
  const bool below_zero = lo_x < -1e-6 || lo_y < -1e-6;
  if (o.fixed_offset && below_zero) {
    e << " It starts below the zero: add at least " << mm(std::max(0.0, -lo_x)) << " "
      << mm(std::max(0.0, -lo_y)) << " mm to --offset.";
  } else if (o.fixed_offset && w + 2 * radius <= o.work_width_mm &&
             h + 2 * radius <= o.work_height_mm) {
    e << " It fits with --offset at most "
      << mm(o.offset_mm.x() - std::max(0.0, hi_x - o.work_width_mm)) << " "
      << mm(o.offset_mm.y() - std::max(0.0, hi_y - o.work_height_mm)) << " mm.";
  } else if (o.margin_mm + 1e-9 < radius) {
    e << " --margin must be at least the tool radius.";
  } else if (fit > 0 && fit < 1e299 && !o.fixed_offset) {
    e << " It fits at --scale " << std::floor(o.scale * fit * 1000) / 1000 << " or smaller";
    if (w + 2 * radius <= o.work_width_mm && h + 2 * radius <= o.work_height_mm) {
      e << ", or at this scale with --margin "
        << mm(std::min(o.work_width_mm - w - radius, o.work_height_mm - h - radius)) << " or less";
    }
    e << ".";
  }
  const double need_w = hi_x - std::min(0.0, lo_x), need_h = hi_y - std::min(0.0, lo_y);
  if (below_zero || o.fixed_offset) {
    // A larger work area cannot help what lies below the zero; an offset was said above.
  } else if (need_w <= o.travel_width_mm + 1e-6 && need_h <= o.travel_height_mm + 1e-6) {
    e << " A larger work area also fits: --work " << mm(std::max(need_w, o.work_width_mm)) << " "
      << mm(std::max(need_h, o.work_height_mm)) << " (the controller's travel is "
      << mm(o.travel_width_mm) << " x " << mm(o.travel_height_mm) << " mm).";
  } else {
    e << " The controller's travel is " << mm(o.travel_width_mm) << " x " << mm(o.travel_height_mm)
      << " mm, so the drawing has to be scaled down.";
  }
  if (!culprit.empty()) e << " First outside: " << culprit << ".";
  throw PlanError(e.str());
}

Point2 offset_point(const BSpline& s, bool at_start, int32_t offset_um) {
  const Point2 p = at_start ? start_point(s) : end_point(s);
  if (offset_um == 0) return p;
  // The tangent from a short chord at the end (the firmware uses the derivative there).
  const double span = s.t_max() - s.t_min();
  Point2 d = at_start ? Point2(evaluate(s, s.t_min() + span * 1e-6) - p)
                      : Point2(p - evaluate(s, s.t_max() - span * 1e-6));
  if (!(d.norm() > 0)) return p;
  d /= d.norm();
  return p + Point2(-d.y(), d.x()) * (offset_um / 1000.0);
}

}  // namespace plan_detail

void check_work_area(double work_width_mm, double work_height_mm, double travel_width_mm,
                     double travel_height_mm) {
  using plan_detail::mm;
  if (!(work_width_mm > 0) || !(work_height_mm > 0)) {
    throw PlanError("--work " + mm(work_width_mm) + " " + mm(work_height_mm) +
                    ": the work area must have a positive width and height");
  }
  if (work_width_mm > travel_width_mm + 1e-9 || work_height_mm > travel_height_mm + 1e-9) {
    throw PlanError(
        "--work " + mm(work_width_mm) + " " + mm(work_height_mm) +
        " mm is beyond the controller's travel of " + mm(travel_width_mm) + " x " +
        mm(travel_height_mm) +
        " mm: the controller would stop the job once the tool got there. Use a work "
        "area within the travel and scale the drawing down (--scale) if it does not fit");
  }
}

namespace plan_detail {

void check_options(const PlanOptions& o) {
  if (!(o.scale > 0) || !std::isfinite(o.scale)) throw PlanError("scale must be positive");
  if (!(o.feed_mm_per_s > 0) || !(o.plunge_mm_per_s > 0)) throw PlanError("feeds must be positive");
  if (!(o.tool_radius_mm >= 0)) throw PlanError("tool radius must not be negative");
  check_work_area(o.work_width_mm, o.work_height_mm, o.travel_width_mm, o.travel_height_mm);
  for (double z : {o.z_up_mm, o.z_down_mm}) {
    if (!(std::fabs(z) <= o.travel_z_mm)) {
      throw PlanError("Z " + mm(z) + " mm is beyond the controller's Z travel of +-" +
                      mm(o.travel_z_mm) + " mm");
    }
  }
}

void append_curve_steps(const PlannedCurve& c, const BSpline& spline, int index, int32_t offset,
                        const PlanOptions& o, JobPlan* plan) {
  const int32_t feed = to_um(o.feed_mm_per_s);
  if (o.lines_as_feeds && offset == 0 && is_polyline(spline)) {
    for (size_t k = 1; k < spline.control.size(); ++k) {
      PlanStep f;
      f.kind = PlanStep::kFeed;
      f.to = to_um(spline.control[k]);
      f.feed_um_per_s = feed;
      f.curve = index;
      plan->steps.push_back(f);
    }
    return;
  }
  try {
    append_spline_steps(spline, index, feed, offset, plan);
  } catch (const ConversionError& e) {
    throw PlanError(describe(c) + ": " + e.what());
  }
}

void append_spline_steps(const BSpline& spline, int index, int32_t feed_um_per_s, int32_t offset_um,
                         JobPlan* plan) {
  const std::vector<core::Spline> pieces = to_firmware_splines(spline);
  for (size_t k = 0; k < pieces.size(); ++k) {
    PlanStep s;
    s.kind = PlanStep::kSpline;
    s.set_spline(StepSpline(pieces[k]));
    s.to = to_um(k + 1 == pieces.size() ? end_point(spline)
                                        : end_point(from_firmware_spline(pieces[k])));
    s.feed_um_per_s = feed_um_per_s;
    s.tool_offset_um = offset_um;
    s.curve = index;
    plan->steps.push_back(s);
  }
}

}  // namespace plan_detail

}  // namespace host
