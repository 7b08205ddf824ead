// Outline loops, cutter offset and tabs (see cutout.h).
#include "host/lib/pcb/cutout.h"

#include <algorithm>  // std::reverse
#include <cmath>      // std::fabs
#include <sstream>    // std::ostringstream

#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

double dist_nm(const IntPoint& a, const IntPoint& b) {
  const double dx = static_cast<double>(a.X - b.X), dy = static_cast<double>(a.Y - b.Y);
  return std::sqrt(dx * dx + dy * dy);
}

// The polyline cut at the given arc lengths (ascending), alternating cut and tab pieces:
// [0, a0) cut, [a0, a1) tab, [a1, a2) cut, ...
std::vector<CutoutPiece> split_at(const std::vector<Point2>& pts, const std::vector<double>& cuts) {
  std::vector<CutoutPiece> out(1);
  out.back().points_mm.push_back(pts.front());
  double at = 0;
  size_t next = 0;
  for (size_t i = 1; i < pts.size(); ++i) {
    const Point2 a = pts[i - 1], b = pts[i];
    const double len = (b - a).norm();
    while (next < cuts.size() && cuts[next] <= at + len) {
      const Point2 p = a + (b - a) * ((cuts[next] - at) / std::max(len, 1e-12));
      out.back().points_mm.push_back(p);
      CutoutPiece piece;
      piece.tab = next % 2 == 0;
      piece.points_mm.push_back(p);
      out.push_back(piece);
      ++next;
    }
    out.back().points_mm.push_back(b);
    at += len;
  }
  return out;
}

}  // namespace

Paths outline_loops(const PcbLayer& outline, double join_tolerance_mm) {
  if (!outline.outline_paths_are_open) return outline.polygons_nm;
  const double tol_nm = join_tolerance_mm * kNmPerMm;
  std::vector<Path> open;
  Paths loops;
  for (const Path& p : outline.polygons_nm) {
    if (p.size() < 2) continue;
    if (p.size() > 2 && dist_nm(p.front(), p.back()) <= tol_nm) {
      loops.push_back(p);
      loops.back().pop_back();
    } else {
      open.push_back(p);
    }
  }
  // Chain strokes: extend the current chain by any stroke starting or ending at its end.
  std::vector<bool> used(open.size(), false);
  for (size_t s = 0; s < open.size(); ++s) {
    if (used[s]) continue;
    used[s] = true;
    Path chain = open[s];
    bool grew = true;
    while (grew && dist_nm(chain.front(), chain.back()) > tol_nm) {
      grew = false;
      for (size_t k = 0; k < open.size(); ++k) {
        if (used[k]) continue;
        Path next = open[k];
        if (dist_nm(next.back(), chain.back()) <= tol_nm) std::reverse(next.begin(), next.end());
        if (dist_nm(next.front(), chain.back()) > tol_nm) continue;
        chain.insert(chain.end(), next.begin() + 1, next.end());
        used[k] = true;
        grew = true;
      }
    }
    if (dist_nm(chain.front(), chain.back()) > tol_nm) {
      std::ostringstream e;
      e << outline.path << ": the board outline does not close: a stroke chain ends at ("
        << to_mm(chain.back()).x() << ", " << to_mm(chain.back()).y()
        << ") mm, nothing continues it within " << join_tolerance_mm << " mm";
      throw CutoutError(e.str());
    }
    chain.pop_back();
    loops.push_back(chain);
  }
  return loops;
}

CutoutPlan plan_cutout(const PcbLayer& outline, const CutoutOptions& o) {
  if (!(o.cutter_diameter_mm > 0)) throw CutoutError("the cutter diameter must be positive");
  const Paths loops = outline_loops(outline, o.join_tolerance_mm);
  if (loops.empty()) throw CutoutError(outline.path + ": the outline layer has no closed loop");
  CutoutPlan plan;
  // Even-odd: the outermost loop is the board, a loop inside it a cut-out, and so on.
  ClipperLib::Clipper c;
  c.AddPaths(loops, ClipperLib::ptSubject, true);
  c.Execute(ClipperLib::ctUnion, plan.board_nm, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
  plan.board_area_mm2 = signed_area(plan.board_nm) / (kNmPerMm * kNmPerMm);
  const Paths cutter = offset_closed(plan.board_nm, o.cutter_diameter_mm * kNmPerMm / 2,
                                     o.arc_tolerance_mm * kNmPerMm);
  std::vector<CutoutLoop> inner, outer;
  for (const Path& p : cutter) {
    CutoutLoop loop;
    loop.outer = ClipperLib::Orientation(p);
    std::vector<Point2> pts;
    for (const IntPoint& q : p) pts.push_back(to_mm(q));
    pts.push_back(pts.front());
    double len = 0;
    for (size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
    int tabs = 0;
    if (loop.outer && o.tab_width_mm > 0) {
      tabs = o.tab_spacing_mm > 0 ? static_cast<int>(len / o.tab_spacing_mm) : o.tab_count;
    }
    const double gap = o.tab_width_mm + o.cutter_diameter_mm;  // path length lifted per tab
    if (tabs > 0 && tabs * gap >= 0.8 * len) tabs = static_cast<int>(0.8 * len / gap);
    std::vector<double> cuts;
    for (int k = 0; k < tabs; ++k) {
      const double centre = (k + 0.5) * len / tabs;
      cuts.push_back(centre - gap / 2);
      cuts.push_back(centre + gap / 2);
    }
    plan.tabs += tabs;
    loop.pieces = split_at(pts, cuts);
    (loop.outer ? outer : inner).push_back(loop);
  }
  plan.loops = inner;
  plan.loops.insert(plan.loops.end(), outer.begin(), outer.end());
  return plan;
}

}  // namespace host::pcb
