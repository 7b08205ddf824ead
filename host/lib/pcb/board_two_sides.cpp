// The board planner's double-sided stage: alignment holes (see board_stages.h).
#include "host/lib/pcb/board_stages.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>  // std::fabs
#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb::board_stages {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

// The board's extents in the file frame, the same for both sides' jobs: its outline, else
// its holes, else this side's copper (with a note).
Extents board_extents_file_mm(const BoardLayers& layers, const PcbLayer* copper,
                              const CutoutPlan& cp, BoardReport& rep) {
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
  return board;
}

// The holes in the file frame, each with its mirror about the axis ('auto': one below and
// one above the board on the axis); refused inside the board or overlapping each other.
std::vector<Point2> alignment_holes_file_mm(const AlignmentOptions& a, const Extents& board,
                                            double axis, double keep_mm) {
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
  return holes;
}

// The top side drills the holes and leaves the cut-out; the bottom side drills nothing.
void split_work_between_sides(const BoardOptions& o, const std::vector<Point2>& holes, double sx,
                              std::vector<DrillTool>& drills, std::vector<Trace>& cut,
                              BoardReport& rep) {
  const AlignmentOptions& a = o.alignment;
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
    if (!cut.empty()) rep.no_cutout = "the bottom side's job cuts the board out";
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

}  // namespace

Extents align_sides(const BoardLayers& layers, const PcbLayer* copper, const CutoutPlan& cp,
                    const BoardOptions& o, double sx, std::vector<DrillTool>& drills,
                    std::vector<Trace>& cut, BoardJob& job) {
  BoardReport& rep = job.report;
  Extents region;  // side-independent, mirrored file frame: placed at the margin
  const AlignmentOptions& a = o.alignment;
  if (!(a.hole_diameter_mm > 0) || !(a.hole_depth_mm > 0))
    throw PlanError("the alignment holes' diameter and depth must be positive");
  const Extents board = board_extents_file_mm(layers, copper, cp, rep);
  if (board.empty()) throw PlanError("alignment holes need a board (outline, drill or copper)");
  const double axis = (board.min.x() + board.max.x()) / 2;
  job.flip_axis_file_x_mm = axis;
  const double r = a.hole_diameter_mm / 2;
  // Clear of the board and of the cut-out's cutter beside it.
  const double keep_mm = r + 2 * o.cutout.cutter_diameter_mm + 1.0;
  const std::vector<Point2> holes = alignment_holes_file_mm(a, board, axis, keep_mm);
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
  split_work_between_sides(o, holes, sx, drills, cut, rep);
  return region;
}

}  // namespace host::pcb::board_stages
