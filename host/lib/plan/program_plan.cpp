// Planning a program (G-code from a CAM program): the operations in file order, nothing
// reordered or reversed, so tool changes, pauses, dwells and holes stay where the program
// put them. Scaling, the lower-left zero and the work-area check are the drawing planner's.
#include <algorithm>  // std::max, std::min
#include <cmath>      // std::isnan, std::llround
#include <sstream>    // std::ostringstream

#include "host/lib/plan/job_plan.h"
#include "host/lib/plan/plan_steps.h"
#include "host/lib/plan/polyline_fit.h"

namespace host {

using namespace plan_detail;

namespace {

// LinuxCNC's G83 clearance above the previous peck's depth before feeding on (0.010 in).
const double kPeckClearanceMm = 0.254;

// What the LCD's 16 columns show of a pause: the message if it fits; for a tool change
// "T1 " and the message's last word (pcb2gcode and FlatCAM end it with the tool size).
std::string lcd_text(const ProgramOp& op) {
  const size_t columns = 16;
  if (op.text.size() <= columns) return op.text;
  if (op.tool != 0) {
    const std::string t = "T" + std::to_string(op.tool);
    const size_t space = op.text.find_last_of(' ');
    const std::string last = space == std::string::npos ? "" : op.text.substr(space + 1);
    if (!last.empty() && t.size() + 1 + last.size() <= columns) return t + " " + last;
    return t + " tool change";
  }
  return op.text.substr(0, columns);
}

class ProgramPlanner {
 public:
  ProgramPlanner(const Drawing& d, const PlanOptions& o) : d_(d), o_(o) {}

  JobPlan plan() {
    place();
    PlanStep up;
    up.kind = PlanStep::kPenUp;
    up.z_um = to_um(o_.z_up_mm);
    push(up);
    z_um_ = up.z_um;
    for (const ProgramOp& op : d_.program) {
      // The program lifted the tool out of the work after the last cut: so does the plan,
      // before the spindle stops or the machine waits.
      if (op.kind != ProgramOp::kCut && cutting_ && op.z_mm > 0) lift_to(to_um(o_.z_up_mm));
      switch (op.kind) {
        case ProgramOp::kCut:
          cut(op);
          break;
        case ProgramOp::kPause:
          pause(op);
          break;
        case ProgramOp::kDwell:
          dwell(op.dwell_s, op);
          break;
        case ProgramOp::kSpindle: {
          PlanStep s;
          s.kind = PlanStep::kSpindle;
          s.spindle_on = op.spindle_on;
          push(s);
          break;
        }
        case ProgramOp::kDrill:
          drill(op);
          break;
      }
    }
    lift_to(to_um(o_.z_up_mm));
    PlanStep home;
    home.kind = PlanStep::kRapid;
    push(home);
    plan_.rapid_length_mm += at_.norm();
    return plan_;
  }

 private:
  // Scale, offset (the lower-left corner of curves and holes at the margin), work area.
  void place() {
    const Eigen::Matrix2d scale = Eigen::Matrix2d::Identity() * o_.scale;
    Extents ext;
    std::vector<BSpline> scaled;
    for (const Curve& c : d_.curves) {
      scaled.push_back(transformed(c.spline(), scale, Point2(0, 0)));
      ext.add(curve_extents(scaled.back()));
    }
    for (const ProgramOp& op : d_.program)
      if (op.kind == ProgramOp::kDrill) ext.add(Point2(op.at * o_.scale));
    if (ext.empty()) throw PlanError(d_.path + ": the program has nothing to engrave or drill");
    plan_.offset_mm =
        o_.fixed_offset ? o_.offset_mm : Point2(Point2(o_.margin_mm, o_.margin_mm) - ext.min);
    const double radius = o_.tool_side == ToolSide::kCentre ? 0.0 : o_.tool_radius_mm;
    std::string culprit;
    planned_index_.assign(d_.curves.size(), -1);
    for (const ProgramOp& op : d_.program) {
      if (op.kind == ProgramOp::kDrill) {
        const Point2 p = hole(op);
        plan_.extents_mm.add(p);
        if (culprit.empty() && (p.x() < -1e-6 || p.y() < -1e-6 || p.x() > o_.work_width_mm + 1e-6 ||
                                p.y() > o_.work_height_mm + 1e-6)) {
          std::ostringstream o;
          o << "the hole of " << op.source << " is at (" << p.x() << ", " << p.y()
            << ") mm in the machine frame";
          culprit = o.str();
        }
        check_z(op.z_start_mm, op);
        check_z(op.z_bottom_mm, op);
        check_z(op.retract_mm, op);
      }
      if (op.kind != ProgramOp::kCut) continue;
      PlannedCurve pc;
      pc.set_spline(transformed(scaled[op.curve], Eigen::Matrix2d::Identity(), plan_.offset_mm));
      pc.drawing_index = op.curve;
      pc.source = d_.curves[op.curve].source;
      planned_index_[op.curve] = static_cast<int>(plan_.curves.size());
      plan_.curves.push_back(pc);
      plan_.extents_mm.add(curve_extents(pc.spline()));
      if (culprit.empty()) culprit = first_exit(pc, radius, o_);
      if (!std::isnan(op.depth_mm)) check_z(op.depth_mm, op);
    }
    check_job_fits(plan_.extents_mm, radius, o_, culprit);
  }

  Point2 hole(const ProgramOp& op) const { return op.at * o_.scale + plan_.offset_mm; }

  void check_z(double z_mm, const ProgramOp& op) const {
    if (std::fabs(z_mm) > o_.travel_z_mm) {
      std::ostringstream o;
      o << d_.path << ": " << op.source << ": Z " << z_mm
        << " mm is beyond the controller's Z travel of +-" << o_.travel_z_mm << " mm";
      throw PlanError(o.str());
    }
  }

  void push(PlanStep s) { plan_.steps.push_back(s); }

  // Raises the tool to z_um if it is lower (a kPenUp: Z at the rapid rate).
  void lift_to(int32_t z_um) {
    if (z_um_ >= z_um) return;
    PlanStep up;
    up.kind = PlanStep::kPenUp;
    up.z_um = z_um;
    push(up);
    cutting_ = false;
    z_um_ = z_um;
  }

  void rapid_to(const Point2& p) {
    PlanStep r;
    r.kind = PlanStep::kRapid;
    r.to = to_um(p);
    push(r);
    plan_.rapid_length_mm += (p - at_).norm();
    at_ = p;
  }

  // Z move at a feed (kPenDown) or at the rapid rate (kPenUp), without the pen-lift count.
  void z_move(int32_t z_um, int32_t feed_um_per_s, int curve) {
    PlanStep s;
    s.kind = feed_um_per_s > 0 ? PlanStep::kPenDown : PlanStep::kPenUp;
    s.z_um = z_um;
    s.feed_um_per_s = feed_um_per_s;
    s.curve = curve;
    push(s);
    z_um_ = z_um;
  }

  void cut(const ProgramOp& op) {
    const int index = planned_index_[op.curve];
    PlannedCurve& c = plan_.curves[index];
    int32_t offset = 0;
    if (o_.tool_side != ToolSide::kCentre) {
      offset = to_um(o_.tool_radius_mm) * (o_.tool_side == ToolSide::kLeft ? 1 : -1);
    }
    const BSpline spline = c.spline();
    const Point2 start = offset_point(spline, true, offset);
    const int32_t depth =
        to_um(o_.file_depths && !std::isnan(op.depth_mm) ? op.depth_mm : o_.z_down_mm);
    const int32_t plunge = to_um(o_.plunge_mm_per_s);
    if (cutting_ && (start - at_).norm() <= o_.chain_tolerance_mm) {
      // Goes on from where the last cut ended: no lift; a new depth is a plunge in place.
      c.chained = true;
      if (to_um(start).x_um != to_um(at_).x_um || to_um(start).y_um != to_um(at_).y_um) {
        PlanStep f;
        f.kind = PlanStep::kFeed;
        f.to = to_um(start);
        f.feed_um_per_s = to_um(o_.feed_mm_per_s);
        f.curve = index;
        push(f);
      }
      if (depth != z_um_) z_move(depth, depth < z_um_ ? plunge : 0, index);
    } else {
      if (cutting_) ++plan_.pen_lifts;  // between two cuts
      lift_to(to_um(o_.z_up_mm));
      rapid_to(start);
      if (z_um_ > to_um(o_.z_up_mm)) z_move(to_um(o_.z_up_mm), 0, index);  // after a tool change
      z_move(depth, plunge, index);
    }
    cutting_ = true;
    if (o_.fit_tolerance_mm > 0 && offset == 0 && is_polyline(spline)) {
      // G1 runs as cubic B-splines; the plan's curve stays the program's own path.
      FitOptions fo;
      fo.tolerance_mm = o_.fit_tolerance_mm;
      for (const BSpline& s : fit_polyline(spline.control, fo))
        append_curve_steps(c, s, index, offset, o_, &plan_);
    } else {
      append_curve_steps(c, spline, index, offset, o_, &plan_);
    }
    plan_.cut_length_mm += curve_length(spline);
    at_ = offset_point(spline, false, offset);
  }

  // The tool goes up (to the program's tool-change height when that is higher, at most
  // pause_z_max_mm) so the operator can change the bit, then the controller waits.
  void pause(const ProgramOp& op) {
    const double z = std::max(o_.z_up_mm, std::min(op.z_mm, o_.pause_z_max_mm));
    lift_to(to_um(z));
    PlanStep p;
    p.kind = PlanStep::kPause;
    p.set_text(lcd_text(op));
    push(p);
  }

  void dwell(double seconds, const ProgramOp&) {
    PlanStep w;
    w.kind = PlanStep::kDwell;
    w.dwell_ms = static_cast<uint32_t>(std::llround(seconds * 1000.0));
    if (w.dwell_ms > 0) push(w);
  }

  // One hole: as the controller's drill command, or as Z moves (always for a dwell at the
  // bottom or pecks, which the drill command does not describe).
  void drill(const ProgramOp& op) {
    const Point2 p = hole(op);
    const int32_t start = to_um(op.z_start_mm), bottom = to_um(op.z_bottom_mm);
    const int32_t feed =
        to_um(op.feed_mm_per_s > 0 ? std::min(op.feed_mm_per_s, o_.drill_feed_max_mm_per_s)
                                   : o_.plunge_mm_per_s);
    lift_to(std::max(to_um(o_.z_up_mm), start));
    ++plan_.holes;
    const bool z_moves = o_.drill_mode == DrillMode::kZMoves || op.dwell_s > 0 || op.peck_mm > 0;
    if (!z_moves) {
      // The drill command travels there itself, at the height the tool is at (>= R).
      plan_.rapid_length_mm += (p - at_).norm();
      PlanStep s;
      s.kind = PlanStep::kDrill;
      s.to = to_um(p);
      s.z_start_um = start;
      s.z_um = bottom;
      s.feed_um_per_s = feed;
      push(s);
      z_um_ = start;
    } else {
      rapid_to(p);
      if (z_um_ != start) z_move(start, 0, -1);
      int32_t depth = start;
      const int32_t peck =
          op.peck_mm > 0 ? std::max<int32_t>(1, to_um(op.peck_mm)) : start - bottom;
      while (depth > bottom) {
        const int32_t next = std::max(bottom, depth - peck);
        if (depth != start) {
          // G83: back into the hole quickly, to just above the last depth.
          z_move(std::min(start, depth + to_um(kPeckClearanceMm)), 0, -1);
        }
        z_move(next, feed, -1);
        if (next == bottom) dwell(op.dwell_s, op);
        if (next != bottom) z_move(start, 0, -1);  // clear the chips
        depth = next;
      }
      z_move(start, 0, -1);
    }
    if (to_um(op.retract_mm) > z_um_) z_move(to_um(op.retract_mm), 0, -1);
    cutting_ = false;
    at_ = p;
  }

  const Drawing& d_;
  const PlanOptions& o_;
  JobPlan plan_;
  std::vector<int> planned_index_;  // drawing curve -> plan curve
  Point2 at_{0, 0};
  int32_t z_um_ = 0;
  bool cutting_ = false;  // the tool is down in the work after a cut
};

}  // namespace

JobPlan plan_program(const Drawing& drawing, const PlanOptions& options) {
  return ProgramPlanner(drawing, options).plan();
}

}  // namespace host
