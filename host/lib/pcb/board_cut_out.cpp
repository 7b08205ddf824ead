// The board planner's cut-out stage (see board_stages.h).
#include "host/lib/pcb/board_stages.h"

#include <fmt/format.h>  // fmt::format
#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb::board_stages {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

std::vector<Trace> cut_out(const BoardLayers& layers, const BoardOptions& o, double sx,
                           CutoutPlan& cp, BoardJob& job) {
  BoardReport& rep = job.report;
  std::vector<Trace> cut;
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
  return cut;
}

}  // namespace host::pcb::board_stages
