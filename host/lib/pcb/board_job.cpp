// The board job planner (see board_job.h).
#include "host/lib/pcb/board_job.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>   // std::min
#include <cmath>       // std::llround, std::ceil
#include <functional>  // std::function
#include <stdexcept>   // std::invalid_argument

#include "host/lib/pcb/drill_order.h"
#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/firmware_spline.h"

namespace host::pcb {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

int32_t um(double mm) {
  return static_cast<int32_t>(std::llround(mm * 1000.0));
}

core::PointUm um(const Point2& p) {
  core::PointUm q;
  q.x_um = um(p.x());
  q.y_um = um(p.y());
  return q;
}

// One traced path of the job before placement: fitted curves in the mirrored file frame.
struct Trace {
  std::vector<BSpline> curves;
  std::string source;
  std::vector<bool> lifted;  // cut-out: per curve, true over a tab
  bool clearing = false;     // isolation cut with the clearing tool
};

struct DrillTool {
  std::string label;
  double diameter_mm = 0;
  double depth_mm = 0;
  std::vector<Point2> holes;                     // mirrored file frame
  std::vector<std::pair<Point2, Point2>> slots;  // mirrored file frame
};

std::vector<Point2> polyline_mm(const Path& p, double sx) {
  std::vector<Point2> out;
  for (const IntPoint& q : p) {
    const Point2 m = to_mm(q);
    out.emplace_back(sx * m.x(), m.y());
  }
  return out;
}

double polyline_length(const std::vector<Point2>& p, bool closed) {
  double l = 0;
  for (size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  if (closed && p.size() > 1) l += (p.front() - p.back()).norm();
  return l;
}

// Builds the plan's steps and curves in the machine frame.
class StepWriter {
 public:
  StepWriter(JobPlan* plan, const BoardOptions& o, const Point2& offset)
      : plan_(plan), o_(o), offset_(offset), place_(o.alignment.placement) {}

  void pen_up(double z_mm) {
    if (!plan_->steps.empty() && plan_->steps.back().kind == PlanStep::kPenUp &&
        plan_->steps.back().z_um == um(z_mm))
      return;
    if (cutting_) ++plan_->pen_lifts;
    cutting_ = false;
    PlanStep s;
    s.kind = PlanStep::kPenUp;
    s.z_um = um(z_mm);
    plan_->steps.push_back(s);
  }
  void pen_down(double z_mm, double feed) {
    cutting_ = true;
    PlanStep s;
    s.kind = PlanStep::kPenDown;
    s.z_um = um(z_mm);
    s.feed_um_per_s = um(feed);
    plan_->steps.push_back(s);
  }
  void rapid(const Point2& machine) {
    plan_->rapid_length_mm += (machine - at_).norm();
    PlanStep s;
    s.kind = PlanStep::kRapid;
    s.to = um(place_.apply(machine));
    plan_->steps.push_back(s);
    at_ = machine;
  }
  // Back to the machine's zero (not turned and shifted with the job).
  void rapid_home() {
    const Point2 home = place_.inverse().apply(Point2(0, 0));
    plan_->rapid_length_mm += (home - at_).norm();
    PlanStep s;
    s.kind = PlanStep::kRapid;
    s.to = um(Point2(0, 0));
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
    pc.spline.degree = 1;
    pc.spline.control = {place_.apply(a), place_.apply(b)};
    pc.spline.knots = {0.0, 0.0, 1.0, 1.0};
    pc.drawing_index = static_cast<int>(plan_->curves.size());
    pc.source = source;
    plan_->curves.push_back(pc);
    return pc.drawing_index;
  }
  void drill(const Point2& machine, double depth_mm) {
    PlanStep s;
    s.curve = reference(machine, machine, "hole");
    s.kind = PlanStep::kDrill;
    s.to = um(place_.apply(machine));
    s.z_start_um = um(o_.drill_start_mm);
    s.z_um = um(-depth_mm);
    s.feed_um_per_s = um(o_.drill_feed_mm_per_s);
    plan_->steps.push_back(s);
    plan_->rapid_length_mm += (machine - at_).norm();
    at_ = machine;
  }
  void feed_to(const Point2& machine, double feed) {
    PlanStep s;
    s.curve = reference(at_, machine, "slot");
    s.kind = PlanStep::kFeed;
    s.to = um(place_.apply(machine));
    s.feed_um_per_s = um(feed);
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
    pc.spline = transformed(file_curve, turn, place_.apply(offset_));
    pc.drawing_index = static_cast<int>(plan_->curves.size());
    pc.chained = chained;
    pc.source = source;
    const int index = static_cast<int>(plan_->curves.size());
    plan_->curves.push_back(pc);
    std::vector<core::Spline> pieces;
    try {
      pieces = to_firmware_splines(pc.spline);
    } catch (const ConversionError& e) {
      throw PlanError(source + ": " + e.what());
    }
    for (size_t k = 0; k < pieces.size(); ++k) {
      PlanStep s;
      s.kind = PlanStep::kSpline;
      s.set_spline(StepSpline(pieces[k]));
      s.to = um(k + 1 == pieces.size() ? end_point(pc.spline)
                                       : end_point(from_firmware_spline(pieces[k])));
      s.feed_um_per_s = um(feed);
      s.curve = index;
      plan_->steps.push_back(s);
    }
    // Length and extents from one sampling (within 1 um).
    const std::vector<Point2> pts = sample(pc.spline, 0.001);
    for (size_t i = 0; i < pts.size(); ++i) {
      plan_->extents_mm.add(pts[i]);
      if (i > 0) plan_->cut_length_mm += (pts[i] - pts[i - 1]).norm();
    }
    at_ = place_.inverse().apply(end_point(pc.spline));
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

void check_options(const BoardOptions& o) {
  if (!(o.isolation_depth_mm > 0)) throw PlanError("the isolation depth must be positive");
  if (!(o.drill_depth_mm > 0) || !(o.cutout_depth_mm > 0) || !(o.cutout_step_mm > 0))
    throw PlanError("drill depth, cut-out depth and cut-out step must be positive");
  if (!(o.feed_mm_per_s > 0) || !(o.plunge_mm_per_s > 0) || !(o.drill_feed_mm_per_s > 0) ||
      !(o.cutout_feed_mm_per_s > 0))
    throw PlanError("feeds must be positive");
  if (!(o.z_travel_mm > 0) || !(o.drill_start_mm > 0))
    throw PlanError("the travel height and the drill start height must be above the board");
  if (!(o.tab_height_mm >= 0 && o.tab_height_mm < o.cutout_depth_mm))
    throw PlanError("the tab height must be below the cut-out depth");
  check_work_area(o.work_width_mm, o.work_height_mm, o.travel_width_mm, o.travel_height_mm);
}

}  // namespace

Paths BoardFrame::to_machine_nm(const Paths& file_nm) const {
  Paths out;
  if (!placement.identity()) {
    for (const Path& p : file_nm) {
      Path q;
      for (const IntPoint& v : p) {
        const Point2 m = to_machine(to_mm(v));
        q.emplace_back(nm_from_mm(m.x()), nm_from_mm(m.y()));
      }
      if (sx < 0) ClipperLib::ReversePath(q);  // mirroring flips orientation: restore it
      out.push_back(q);
    }
    return out;
  }
  const ClipperLib::cInt ox = nm_from_mm(offset_mm.x()), oy = nm_from_mm(offset_mm.y());
  for (const Path& p : file_nm) {
    Path q;
    for (const IntPoint& v : p) q.emplace_back(sx < 0 ? -v.X + ox : v.X + ox, v.Y + oy);
    if (sx < 0) ClipperLib::ReversePath(q);  // mirroring flips orientation: restore it
    out.push_back(q);
  }
  return out;
}

std::string describe_gap(const NarrowGap& g, const IsolationOptions& o) {
  const std::string need =
      o.clearance_mm > 0
          ? fmt::format("{:.3f} mm (tool {:.3f} mm + 2 x {:.3f} mm clearance)",
                        o.tool_width_mm + 2 * o.clearance_mm, o.tool_width_mm, o.clearance_mm)
          : fmt::format("tool {:.3f} mm", o.tool_width_mm);
  return fmt::format("gap {:.3f} mm < {} between islands {} and {} at ({:.3f}, {:.3f}) mm",
                     g.gap_mm, need, g.island_a, g.island_b, g.at.x / kNmPerMm, g.at.y / kNmPerMm);
}

std::string tool_label(const char* what, double diameter_mm) {
  std::string s = fmt::format("{} {:.2f}mm", what, diameter_mm);
  if (s.size() > 16) s = fmt::format("{:.2f}mm", diameter_mm);
  return s.substr(0, 16);
}

BoardJob plan_board(const BoardLayers& given, const BoardOptions& o) {
  check_options(o);
  BoardJob job;
  BoardReport& rep = job.report;
  BoardLayers layers = given;
  if (layers.outline && layers.outline->polygons_nm.empty()) {
    // KiCad writes an Edge.Cuts file holding only its aperture list when no outline is drawn.
    rep.notes.push_back(layers.outline->path +
                        ": the outline layer draws nothing: planned without a cut-out");
    layers.outline = nullptr;
  }
  const double sx = o.side == BoardSide::kBottom ? -1.0 : 1.0;
  job.frame.sx = sx;
  const PcbLayer* copper = o.side == BoardSide::kBottom ? layers.copper_bottom : layers.copper_top;
  if (!copper && !layers.drill && !layers.outline)
    throw PlanError(o.side == BoardSide::kBottom
                        ? "nothing to do: no bottom copper, drill or outline layer given"
                        : "nothing to do: no top copper, drill or outline layer given");

  // ---- Isolation (file frame), then fitted curves (mirrored file frame) ----
  std::vector<Trace> iso;
  IsolationResult iso_result;
  if (copper) {
    IsolationOptions io = o.isolation;
    if (io.mill_all && io.area_nm.empty() && layers.outline) {
      io.area_nm = plan_cutout(*layers.outline, o.cutout).board_nm;
    }
    try {
      iso_result = plan_isolation(copper->polygons_nm, io);
    } catch (const std::invalid_argument& e) {
      throw PlanError(e.what());
    }
    rep.islands = iso_result.islands;
    rep.narrow_gaps = iso_result.narrow_gaps;
    if (iso_result.empty_holes_skipped > 0)
      rep.notes.push_back(fmt::format(
          "{}: {} opening(s) in the copper hold no other island (a hatched pour): no contour "
          "inside them (--isolate-empty-holes cuts them)",
          copper->path, iso_result.empty_holes_skipped));
    if (!rep.narrow_gaps.empty() && !o.allow_narrow_gaps) {
      std::string msg = fmt::format(
          "{}: {} place(s) where the copper is closer than the tool width {:.3f} mm plus its "
          "clearance, so the tool cannot separate the islands:",
          copper->path, rep.narrow_gaps.size(), io.tool_width_mm);
      for (size_t i = 0; i < rep.narrow_gaps.size() && i < 20; ++i)
        msg += "\n  " + describe_gap(rep.narrow_gaps[i], io);
      if (rep.narrow_gaps.size() > 20) msg += "\n  ...";
      msg += "\nUse a narrower tool (--tool-width) or plan anyway (--allow-narrow-gaps).";
      throw PlanError(msg);
    }
    FitOptions fo;
    fo.tolerance_mm = o.fit_tolerance_mm;
    for (size_t i = 0; i < iso_result.paths.size(); ++i) {
      const ToolPathNm& t = iso_result.paths[i];
      const std::vector<Point2> pts = polyline_mm(t.path, sx);
      if (pts.size() < 2) continue;
      Trace tr;
      tr.curves = fit_polyline(pts, t.closed, fo, &rep.fit);
      if (tr.curves.empty()) continue;
      tr.source = fmt::format("{} contour {} (pass {})", t.clearing ? "clearing" : "isolation", i,
                              t.pass + 1);
      tr.clearing = t.clearing;
      rep.isolation_vertices += t.path.size() + (t.closed ? 1 : 0);
      rep.isolation_length_mm += polyline_length(pts, t.closed);
      iso.push_back(tr);
    }
    rep.isolation_contours = iso.size();
    job.tool_radius_mm = iso_result.tool_radius_mm;
    job.clearing_tool_radius_mm = iso_result.clearing_tool_radius_mm;
  }

  // ---- Drilling ----
  std::vector<DrillTool> drills;
  if (layers.drill) {
    const PcbLayer& d = *layers.drill;
    std::vector<Point2> at;
    std::vector<double> dia;
    std::vector<int> tool;
    for (const Hole& h : d.holes) {
      const Point2 m = to_mm(IntPoint(h.at.x, h.at.y));
      at.emplace_back(sx * m.x(), m.y());
      dia.push_back(static_cast<double>(h.diameter_nm) / kNmPerMm);
      tool.push_back(h.tool);
    }
    rep.holes = at.size();
    if (copper) {
      // Alignment check: plated holes sit in pads.
      const std::vector<Island> islands = copper_islands(copper->polygons_nm);
      for (const Hole& h : d.holes) {
        const IntPoint c(h.at.x, h.at.y);
        for (const Island& is : islands) {
          if (c.X < is.box.min_x || c.X > is.box.max_x || c.Y < is.box.min_y || c.Y > is.box.max_y)
            continue;
          int inside = ClipperLib::PointInPolygon(c, is.paths[0]) != 0;
          for (size_t k = 1; k < is.paths.size() && inside; ++k)
            inside = ClipperLib::PointInPolygon(c, is.paths[k]) != 1;
          if (inside) {
            ++rep.holes_on_copper;
            break;
          }
        }
      }
    }
    rep.slots = d.slots.size();
    Extents ext;
    for (const Point2& p : at) ext.add(p);
    const DrillPlan dp = order_holes(at, dia, tool, ext.empty() ? Point2(0, 0) : ext.min);
    rep.drill_travel_file_order_mm = dp.travel_file_order_mm;
    rep.drill_travel_ordered_mm = dp.travel_ordered_mm;
    for (const DrillGroup& g : dp.groups) {
      DrillTool t;
      t.diameter_mm = g.diameter_mm;
      t.label = tool_label("Drill", g.diameter_mm);
      t.depth_mm = o.drill_depth_mm;
      t.holes = g.holes_mm;
      drills.push_back(t);
    }
    for (const Slot& s : d.slots) {
      const double dm = static_cast<double>(s.diameter_nm) / kNmPerMm;
      const Point2 a = to_mm(IntPoint(s.from.x, s.from.y)), b = to_mm(IntPoint(s.to.x, s.to.y));
      DrillTool* t = nullptr;
      for (DrillTool& x : drills)
        if (std::llround(x.diameter_mm * 1000) == std::llround(dm * 1000)) t = &x;
      if (!t) {
        drills.emplace_back();
        t = &drills.back();
        t->diameter_mm = dm;
        t->label = tool_label("Drill", dm);
        t->depth_mm = o.drill_depth_mm;
      }
      t->slots.emplace_back(Point2(sx * a.x(), a.y()), Point2(sx * b.x(), b.y()));
    }
    rep.drill_tools = drills.size();
  }

  // ---- Cut-out ----
  std::vector<Trace> cut;
  CutoutPlan cp;
  if (layers.outline) {
    cp = plan_cutout(*layers.outline, o.cutout);
    rep.notes.insert(rep.notes.end(), cp.notes.begin(), cp.notes.end());
    rep.tabs = cp.tabs;
    FitOptions fo;
    fo.tolerance_mm = o.fit_tolerance_mm;
    for (size_t l = 0; l < cp.loops.size(); ++l) {
      Trace tr;
      tr.source = fmt::format("cut-out loop {}", l);
      for (const CutoutPiece& piece : cp.loops[l].pieces) {
        std::vector<Point2> pts;
        for (const Point2& p : piece.points_mm) pts.emplace_back(sx * p.x(), p.y());
        rep.cutout_length_mm += polyline_length(pts, false);
        for (const BSpline& b : fit_polyline(pts, false, fo, nullptr)) {
          tr.curves.push_back(b);
          tr.lifted.push_back(piece.tab);
        }
      }
      if (!tr.curves.empty()) cut.push_back(tr);
    }
    job.cutter_radius_mm = o.cutout.cutter_diameter_mm / 2;
  }

  // ---- Double-sided: one frame for both setups, alignment holes ----
  Extents region;  // side-independent, mirrored file frame: placed at the margin
  if (o.alignment.enabled) {
    const AlignmentOptions& a = o.alignment;
    if (!(a.hole_diameter_mm > 0) || !(a.hole_depth_mm > 0))
      throw PlanError("the alignment holes' diameter and depth must be positive");
    // The board's extents in the file frame, the same for both sides' jobs.
    Extents board;
    if (layers.outline) {
      for (const Path& p : cp.board_nm)
        for (const IntPoint& v : p) board.add(to_mm(v));
    } else if (layers.drill) {
      for (const Hole& h : layers.drill->holes) board.add(to_mm(IntPoint(h.at.x, h.at.y)));
    } else if (copper) {
      for (const Path& p : copper->polygons_nm)
        for (const IntPoint& v : p) board.add(to_mm(v));
      rep.notes.push_back(
          "alignment: the flip axis is the middle of this side's copper (no outline or drill "
          "file): give the same outline or drill file to both sides' jobs so their axes agree");
    }
    if (board.empty()) throw PlanError("alignment holes need a board (outline, drill or copper)");
    const double axis = (board.min.x() + board.max.x()) / 2;
    job.flip_axis_file_x_mm = axis;
    const double r = a.hole_diameter_mm / 2;
    // Clear of the board and of the cut-out's cutter beside it.
    const double keep_mm = r + 2 * o.cutout.cutter_diameter_mm + 1.0;
    std::vector<Point2> holes;
    if (a.holes_file_mm.empty()) {
      holes = {Point2(axis, board.min.y() - keep_mm), Point2(axis, board.max.y() + keep_mm)};
    } else {
      for (const Point2& h : a.holes_file_mm) {
        if (h.x() > board.min.x() - keep_mm && h.x() < board.max.x() + keep_mm &&
            h.y() > board.min.y() - keep_mm && h.y() < board.max.y() + keep_mm)
          throw PlanError(fmt::format(
              "alignment hole at ({:.3f}, {:.3f}) mm is not outside the board ({:.3f} .. {:.3f} "
              "x {:.3f} .. {:.3f} mm) by {:.3f} mm",
              h.x(), h.y(), board.min.x(), board.max.x(), board.min.y(), board.max.y(), keep_mm));
        holes.push_back(h);
        if (std::fabs(h.x() - axis) > 0.001) holes.emplace_back(2 * axis - h.x(), h.y());
      }
    }
    // Holes given twice, or a hole overlapping its own mirror image or another's, would be
    // drilled into each other: no pin stands in them.
    for (size_t i = 0; i < holes.size(); ++i)
      for (size_t k = i + 1; k < holes.size(); ++k)
        if ((holes[i] - holes[k]).norm() < a.hole_diameter_mm)
          throw PlanError(fmt::format(
              "alignment holes at ({:.3f}, {:.3f}) and ({:.3f}, {:.3f}) mm (file frame, with "
              "their mirror images about the flip axis x = {:.3f} mm) overlap: holes of {:.2f} "
              "mm need their centres that far apart; give each hole once",
              holes[i].x(), holes[i].y(), holes[k].x(), holes[k].y(), axis, a.hole_diameter_mm));
    for (const Point2& h : holes) {
      region.add(Point2(sx * h.x() - r, h.y() - r));
      region.add(Point2(sx * h.x() + r, h.y() + r));
    }
    // The board and its mirror image: the same region from either side.
    for (const Point2& c : {board.min, board.max}) {
      region.add(Point2(sx * c.x(), c.y()));
      region.add(Point2(sx * (2 * axis - c.x()), c.y()));
    }
    const double grow_mm = o.cutout.cutter_diameter_mm + 1.0;
    region.add(region.min - Point2(grow_mm, grow_mm));
    for (const Point2& h : holes) job.alignment_holes_mm.push_back(Point2(sx * h.x(), h.y()));
    if (o.side == BoardSide::kTop) {
      // First setup: the holes, through the blank into the spoil board; the cut-out waits for
      // the second setup (the blank must stay whole to be turned over).
      DrillTool pins;
      pins.diameter_mm = a.hole_diameter_mm;
      pins.depth_mm = a.hole_depth_mm;
      pins.label = tool_label("Pins", a.hole_diameter_mm);
      for (const Point2& h : holes) pins.holes.emplace_back(sx * h.x(), h.y());
      drills.push_back(pins);
      rep.holes += pins.holes.size();
      rep.drill_tools = drills.size();
      if (!cut.empty())
        rep.notes.push_back("alignment: the cut-out is left for the bottom side's job");
      cut.clear();
      rep.tabs = 0;
      rep.cutout_length_mm = 0;
    } else {
      if (!drills.empty())
        rep.notes.push_back("alignment: the holes were drilled with the top side: not again");
      drills.clear();
      rep.holes = 0;
      rep.slots = 0;
      rep.drill_tools = 0;
      rep.drill_travel_ordered_mm = rep.drill_travel_file_order_mm = 0;
    }
  }

  // ---- Placement: the tool's lower-left extent at (margin, margin) ----
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
    const RigidTransform& place = o.alignment.placement;
    const Extents placed = tool_extents([&](const Point2& p) { return place.apply(p + offset); });
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

  // ---- Steps ----
  StepWriter w(&plan, o, offset);
  w.pen_up(o.z_travel_mm);
  // The isolation tool's contours, then the clearing tool's, each nearest start next.
  auto cut_isolation = [&](bool clearing) {
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
  };
  cut_isolation(false);
  job.isolation_curves = plan.curves.size();
  cut_isolation(true);
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

  // ---- What the checks and the plot need, in the machine frame ----
  if (copper) {
    job.copper_machine_nm = union_of(job.frame.to_machine_nm(copper->polygons_nm));
    for (size_t i = 0; i < job.isolation_curves + job.clearing_curves; ++i) {
      std::vector<std::vector<Point2>>& paths =
          i < job.isolation_curves ? job.isolation_paths_mm : job.clearing_paths_mm;
      std::vector<Point2> pts;
      for (const PlanStep& s : plan.steps) {
        if (s.kind != PlanStep::kSpline || s.curve != static_cast<int>(i)) continue;
        const std::vector<Point2> piece =
            sample(from_firmware_spline(s.spline().firmware()), 0.0005);
        pts.insert(pts.end(), piece.begin() + (pts.empty() ? 0 : 1), piece.end());
      }
      if (plan.curves[i].chained && !paths.empty()) {
        std::vector<Point2>& last = paths.back();
        last.insert(last.end(), pts.begin() + (pts.empty() ? 0 : 1), pts.end());
      } else {
        paths.push_back(pts);
      }
    }
  }
  if (layers.drill) {
    for (const Hole& h : layers.drill->holes) {
      Hole m = h;
      const Point2 p = job.frame.to_machine(to_mm(IntPoint(h.at.x, h.at.y)));
      m.at.x = nm_from_mm(p.x());
      m.at.y = nm_from_mm(p.y());
      job.holes_machine.push_back(m);
    }
    for (const Slot& s : layers.drill->slots) {
      Slot m = s;
      const Point2 a = job.frame.to_machine(to_mm(IntPoint(s.from.x, s.from.y)));
      const Point2 b = job.frame.to_machine(to_mm(IntPoint(s.to.x, s.to.y)));
      m.from.x = nm_from_mm(a.x()), m.from.y = nm_from_mm(a.y());
      m.to.x = nm_from_mm(b.x()), m.to.y = nm_from_mm(b.y());
      job.slots_machine.push_back(m);
    }
  }
  if (layers.outline) job.board_machine_nm = union_of(job.frame.to_machine_nm(cp.board_nm));
  const size_t first_cutout = job.isolation_curves + job.clearing_curves;
  for (size_t i = first_cutout; i < plan.curves.size(); ++i) {
    if (plan.curves[i].source == "hole" || plan.curves[i].source == "slot") continue;
    const std::vector<Point2> pts = sample(plan.curves[i].spline, 0.002);
    if (plan.curves[i].chained && !job.cutout_paths_mm.empty() && i > first_cutout) {
      std::vector<Point2>& last = job.cutout_paths_mm.back();
      last.insert(last.end(), pts.begin() + 1, pts.end());
    } else {
      job.cutout_paths_mm.push_back(pts);
    }
  }
  return job;
}

}  // namespace host::pcb
