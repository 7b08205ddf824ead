// The board planner's placement and steps (see board_stages.h).
#include "host/lib/pcb/board_stages.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>   // std::min
#include <cmath>       // std::ceil
#include <functional>  // std::function

#include "host/lib/drawing/conics.h"  // line_spline
#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/firmware_spline.h"
#include "host/lib/plan/plan_steps.h"  // plan_detail::to_um, append_spline_steps

namespace host::pcb::board_stages {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

using plan_detail::to_um;  // mm -> um, rounded (the drawings' planner's rounding)

// Builds the plan's steps and curves in the machine frame.
class StepWriter {
 public:
  StepWriter(JobPlan* plan, const BoardOptions& o, const Point2& offset)
      : plan_(plan), o_(o), offset_(offset), place_(o.alignment.placement) {}

  void pen_up(double z_mm) {
    if (!plan_->steps.empty() && plan_->steps.back().kind == PlanStep::kPenUp &&
        plan_->steps.back().z_um == to_um(z_mm))
      return;
    if (cutting_) ++plan_->pen_lifts;
    cutting_ = false;
    PlanStep s;
    s.kind = PlanStep::kPenUp;
    s.z_um = to_um(z_mm);
    plan_->steps.push_back(s);
  }
  void pen_down(double z_mm, double feed) {
    cutting_ = true;
    PlanStep s;
    s.kind = PlanStep::kPenDown;
    s.z_um = to_um(z_mm);
    s.feed_um_per_s = to_um(feed);
    plan_->steps.push_back(s);
  }
  void rapid(const Point2& machine) {
    plan_->rapid_length_mm += (machine - at_).norm();
    PlanStep s;
    s.kind = PlanStep::kRapid;
    s.to = to_um(place_.apply(machine));
    plan_->steps.push_back(s);
    at_ = machine;
  }
  // Back to the machine's zero (not turned and shifted with the job).
  void rapid_home() {
    const Point2 home = place_.inverse().apply(Point2(0, 0));
    plan_->rapid_length_mm += (home - at_).norm();
    PlanStep s;
    s.kind = PlanStep::kRapid;
    s.to = to_um(Point2(0, 0));
    plan_->steps.push_back(s);
    at_ = home;
  }
  void spindle(bool on) {
    if (!o_.spindle || on == spindle_on_) return;
    PlanStep s;
    s.kind = PlanStep::kSpindle;
    s.spindle_on = on;
    plan_->steps.push_back(s);
    spindle_on_ = on;
    if (on && o_.spindle_spinup_ms > 0) {
      PlanStep d;
      d.kind = PlanStep::kDwell;
      d.dwell_ms = o_.spindle_spinup_ms;
      plan_->steps.push_back(d);
    }
  }
  // A tool change: stop the spindle, wait for the operator, start it again. The first tool
  // of the job is mounted before it starts (no pause).
  void tool(const std::string& label, double diameter_mm, BoardJob* job) {
    BoardReport* report = &job->report;
    job->tools.push_back(BoardTool{label, diameter_mm});
    if (tools_ == 0) {
      report->first_tool = label;
    } else {
      pen_up(o_.z_travel_mm);
      spindle(false);
      PlanStep s;
      s.kind = PlanStep::kPause;
      s.set_text(label);
      plan_->steps.push_back(s);
      ++report->tool_changes;
    }
    ++tools_;
    spindle(true);
  }
  // A planned point or straight line (machine frame) for the simulator's contour error:
  // holes and slots are where the tool is down too.
  int reference(const Point2& a, const Point2& b, const std::string& source) {
    PlannedCurve pc;
    pc.set_spline(line_spline(place_.apply(a), place_.apply(b)));
    pc.drawing_index = static_cast<int>(plan_->curves.size());
    pc.source = source;
    plan_->curves.push_back(pc);
    return pc.drawing_index;
  }
  void drill(const Point2& machine, double depth_mm) {
    PlanStep s;
    s.curve = reference(machine, machine, "hole");
    s.kind = PlanStep::kDrill;
    s.to = to_um(place_.apply(machine));
    s.z_start_um = to_um(o_.drill_start_mm);
    s.z_um = to_um(-depth_mm);
    s.feed_um_per_s = to_um(o_.drill_feed_mm_per_s);
    plan_->steps.push_back(s);
    plan_->rapid_length_mm += (machine - at_).norm();
    at_ = machine;
  }
  void feed_to(const Point2& machine, double feed) {
    PlanStep s;
    s.curve = reference(at_, machine, "slot");
    s.kind = PlanStep::kFeed;
    s.to = to_um(place_.apply(machine));
    s.feed_um_per_s = to_um(feed);
    plan_->steps.push_back(s);
    plan_->cut_length_mm += (machine - at_).norm();
    at_ = machine;
  }
  // One fitted curve (file frame, mirrored) traced with the tool down; returns its index.
  int curve(const BSpline& file_curve, const std::string& source, bool chained, double feed) {
    PlannedCurve pc;
    // The placement turns and shifts the control points: B-splines are affine invariant.
    Eigen::Matrix2d turn;
    turn << std::cos(place_.rotation_rad), -std::sin(place_.rotation_rad),
        std::sin(place_.rotation_rad), std::cos(place_.rotation_rad);
    const BSpline spline = transformed(file_curve, turn, place_.apply(offset_));
    pc.set_spline(spline);
    pc.drawing_index = static_cast<int>(plan_->curves.size());
    pc.chained = chained;
    pc.source = source;
    const int index = static_cast<int>(plan_->curves.size());
    plan_->curves.push_back(pc);
    try {
      plan_detail::append_spline_steps(spline, index, to_um(feed), 0, plan_);
    } catch (const ConversionError& e) {
      throw PlanError(source + ": " + e.what());
    }
    // Length and extents from one sampling (within 1 um).
    const std::vector<Point2> pts = sample(spline, 0.001);
    for (size_t i = 0; i < pts.size(); ++i) {
      plan_->extents_mm.add(pts[i]);
      if (i > 0) plan_->cut_length_mm += (pts[i] - pts[i - 1]).norm();
    }
    at_ = place_.inverse().apply(end_point(spline));
    return index;
  }
  Point2 at() const { return at_; }

 private:
  JobPlan* plan_;
  const BoardOptions& o_;
  Point2 offset_;
  RigidTransform place_;  // the measured placement (identity: none)
  Point2 at_{0, 0};       // before the placement
  bool spindle_on_ = false;
  bool cutting_ = false;
  int tools_ = 0;
};

// The isolation tool's contours (or the clearing tool's), each nearest start next.
void write_isolation(const std::vector<Trace>& iso, bool clearing, const Point2& offset,
                     const BoardOptions& o, StepWriter& w, BoardJob& job) {
  std::vector<const Trace*> todo;
  for (const Trace& t : iso)
    if (t.clearing == clearing) todo.push_back(&t);
  if (todo.empty()) return;
  if (clearing)
    w.tool(tool_label("Clear", o.isolation.clearing_tool_width_mm),
           o.isolation.clearing_tool_width_mm, &job);
  else
    w.tool(tool_label("V-bit", o.isolation.tool_width_mm), o.isolation.tool_width_mm, &job);
  std::vector<bool> done(todo.size(), false);
  for (size_t n = 0; n < todo.size(); ++n) {
    size_t best = 0;
    double best_d = 1e300;
    for (size_t i = 0; i < todo.size(); ++i) {
      if (done[i]) continue;
      const double d = (start_point(todo[i]->curves.front()) + offset - w.at()).squaredNorm();
      if (d < best_d) best_d = d, best = i;
    }
    done[best] = true;
    const Trace& t = *todo[best];
    w.pen_up(o.z_travel_mm);
    w.rapid(start_point(t.curves.front()) + offset);
    w.pen_down(-o.isolation_depth_mm, o.plunge_mm_per_s);
    for (size_t k = 0; k < t.curves.size(); ++k)
      w.curve(t.curves[k], t.source, k > 0, o.feed_mm_per_s);
  }
}

}  // namespace

Point2 place(const std::vector<Trace>& iso, const std::vector<Trace>& cut,
             const std::vector<DrillTool>& drills, const Extents& region, const BoardOptions& o,
             BoardJob& job) {
  // The tools' extents with every point taken through `place` (the mirrored file frame
  // into the machine's); a circle's extent is the same turned or not.
  auto tool_extents = [&](const std::function<Point2(const Point2&)>& place) {
    Extents ext;
    auto grow = [&](const Extents& e, double r) {
      if (e.empty()) return;
      ext.add(Point2(e.min.x() - r, e.min.y() - r));
      ext.add(Point2(e.max.x() + r, e.max.y() + r));
    };
    auto extents_of = [&](const std::vector<Point2>& pts) {
      Extents e;
      for (const Point2& p : pts) e.add(place(p));
      return e;
    };
    for (const Trace& t : iso)
      for (const BSpline& b : t.curves)
        grow(extents_of(sample(b, 0.001)),
             t.clearing ? job.clearing_tool_radius_mm : job.tool_radius_mm);
    for (const Trace& t : cut)
      for (const BSpline& b : t.curves) grow(extents_of(sample(b, 0.001)), job.cutter_radius_mm);
    for (const DrillTool& d : drills) {
      std::vector<Point2> pts = d.holes;
      for (const auto& s : d.slots) pts.push_back(s.first), pts.push_back(s.second);
      grow(extents_of(pts), d.diameter_mm / 2);
    }
    return ext;
  };
  const Extents ext = tool_extents([](const Point2& p) { return p; });
  if (ext.empty()) throw PlanError("nothing to do: the layers hold no copper, hole or outline");
  // Double-sided: the side-independent region at the margin (both jobs in one frame).
  const Point2 offset = Point2(o.margin_mm, o.margin_mm) - (region.empty() ? ext.min : region.min);
  job.frame.offset_mm = offset;
  job.frame.placement = o.alignment.placement;
  for (Point2& h : job.alignment_holes_mm) h += offset;
  if (ext.min.x() + offset.x() < 0 || ext.min.y() + offset.y() < 0)
    throw PlanError(
        fmt::format("the board job reaches {:.2f} mm beyond the machine zero: raise the margin",
                    -std::min(ext.min.x() + offset.x(), ext.min.y() + offset.y())));
  const double need_w = ext.max.x() + offset.x(), need_h = ext.max.y() + offset.y();
  if (need_w > o.work_width_mm + 1e-6 || need_h > o.work_height_mm + 1e-6) {
    throw PlanError(fmt::format(
        "the board job needs {:.2f} x {:.2f} mm (tool extents plus the {:.1f} mm margin) but the "
        "work area is {:.1f} x {:.1f} mm",
        need_w, need_h, o.margin_mm, o.work_width_mm, o.work_height_mm));
  }
  if (!o.alignment.placement.identity()) {
    // Turned and shifted onto the measured holes, the job must still lie on the work area.
    const RigidTransform& placement = o.alignment.placement;
    const Extents placed =
        tool_extents([&](const Point2& p) { return placement.apply(p + offset); });
    if (placed.min.x() < -1e-6 || placed.min.y() < -1e-6 ||
        placed.max.x() > o.work_width_mm + 1e-6 || placed.max.y() > o.work_height_mm + 1e-6)
      throw PlanError(fmt::format(
          "turned and shifted onto the measured alignment holes, the board job spans ({:.2f}, "
          "{:.2f}) .. ({:.2f}, {:.2f}) mm (tool extents) but the work area is (0, 0) .. "
          "({:.1f}, {:.1f}) mm: place the blank on the work area and measure its holes again",
          placed.min.x(), placed.min.y(), placed.max.x(), placed.max.y(), o.work_width_mm,
          o.work_height_mm));
  }
  JobPlan& plan = job.plan;
  plan.offset_mm = offset;

  return offset;
}

void write_steps(const std::vector<Trace>& iso, const std::vector<Trace>& cut,
                 const std::vector<DrillTool>& drills, const Point2& offset, const BoardOptions& o,
                 BoardJob& job) {
  JobPlan& plan = job.plan;
  StepWriter w(&plan, o, offset);
  w.pen_up(o.z_travel_mm);
  write_isolation(iso, false, offset, o, w, job);
  job.isolation_curves = plan.curves.size();
  write_isolation(iso, true, offset, o, w, job);
  job.clearing_curves = plan.curves.size() - job.isolation_curves;
  for (const DrillTool& d : drills) {
    w.tool(d.label, d.diameter_mm, &job);
    for (const Point2& h : d.holes) w.drill(h + offset, d.depth_mm);
    for (const auto& s : d.slots) {
      w.pen_up(o.z_travel_mm);
      w.rapid(s.first + offset);
      w.pen_down(-o.drill_depth_mm, o.drill_feed_mm_per_s);
      w.feed_to(s.second + offset, o.drill_feed_mm_per_s);
    }
    w.pen_up(o.z_travel_mm);
  }
  if (!cut.empty()) {
    w.tool(tool_label("Cutter", o.cutout.cutter_diameter_mm), o.cutout.cutter_diameter_mm, &job);
    const int passes = static_cast<int>(std::ceil(o.cutout_depth_mm / o.cutout_step_mm - 1e-9));
    const double tab_top = -(o.cutout_depth_mm - o.tab_height_mm);
    for (const Trace& t : cut) {
      for (size_t k = 0; k < t.curves.size(); ++k) {
        if (!t.lifted[k]) continue;
        std::vector<Point2> tab;
        for (const Point2& q : sample(t.curves[k], 0.002))
          tab.push_back(o.alignment.placement.apply(q + offset));
        job.tab_paths_mm.push_back(tab);
      }
    }
    for (const Trace& t : cut) {
      for (int p = 1; p <= passes; ++p) {
        const double z = -std::min(o.cutout_depth_mm, p * o.cutout_step_mm);
        w.pen_up(o.z_travel_mm);
        w.rapid(start_point(t.curves.front()) + offset);
        w.pen_down(z, o.plunge_mm_per_s);
        for (size_t k = 0; k < t.curves.size(); ++k) {
          const bool lift = t.lifted[k] && z < tab_top;
          if (lift) w.pen_up(tab_top);
          w.curve(t.curves[k], fmt::format("{} (depth {:.2f} mm)", t.source, -z), k > 0,
                  o.cutout_feed_mm_per_s);
          if (lift) w.pen_down(z, o.plunge_mm_per_s);
        }
      }
    }
  }
  w.spindle(false);
  w.pen_up(o.z_travel_mm);
  w.rapid_home();
}

}  // namespace host::pcb::board_stages
