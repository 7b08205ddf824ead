// Outline loops, cutter offset and tabs (see cutout.h).
#include "host/lib/pcb/cutout.h"

#include <algorithm>  // std::reverse
#include <cmath>      // std::fabs
#include <sstream>    // std::ostringstream
#include <string>     // std::string
#include <utility>    // std::pair

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

namespace {

// Where the centre lines, chained end to end within `tol_nm`, leave a chain open (for the
// refusal's message); false when every chain closes.
bool open_chain_end(const std::vector<Path>& open, double tol_nm, IntPoint& end) {
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
      end = chain.back();
      return true;
    }
  }
  return false;
}

// A face of the plane the strokes enclose, grown back by the stroke radius to the strokes'
// centre lines; positive for board, negative for a cut-out.
void add_face(const Path& hole, double radius_nm, bool board, Paths& loops) {
  Path face = hole;
  if (!ClipperLib::Orientation(face)) ClipperLib::ReversePath(face);
  ClipperLib::ClipperOffset off(1000.0);  // keep every corner the centre lines have
  off.AddPath(face, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  Paths grown;
  off.Execute(grown, radius_nm);
  for (Path& p : grown) {
    if (ClipperLib::Orientation(p) != board) ClipperLib::ReversePath(p);
    loops.push_back(std::move(p));
  }
}

std::string mm_point(const IntPoint& p) {
  std::ostringstream o;
  o << "(" << to_mm(p).x() << ", " << to_mm(p).y() << ") mm";
  return o.str();
}

}  // namespace

Paths outline_loops(const PcbLayer& outline, double join_tolerance_mm,
                    std::vector<std::string>* notes) {
  if (!outline.outline_paths_are_open) {
    Paths even_odd;
    ClipperLib::Clipper c;
    c.AddPaths(outline.polygons_nm, ClipperLib::ptSubject, true);
    c.Execute(ClipperLib::ctUnion, even_odd, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
    return even_odd;
  }
  // The strokes as drawn, unioned: duplicates, overlaps and T-junctions merge, and ends
  // closer than the stroke width meet (as in gerbv's picture). The chaining tolerance is the
  // widest stroke (at least join_tolerance_mm); the faces the strokes enclose, grown back by
  // half of it, are the loops.
  double width_nm = join_tolerance_mm * kNmPerMm;
  for (ClipperLib::cInt w : outline.outline_widths_nm) width_nm = std::max(width_nm, double(w));
  const double radius_nm = width_nm / 2 + 1000;  // 1 um more: ends exactly a width apart meet
  std::vector<Path> strokes;
  Paths open_strokes, closed_strokes;
  for (const Path& p : outline.polygons_nm) {
    if (p.size() < 2) continue;
    strokes.push_back(p);
    (p.size() > 2 && p.front() == p.back() ? closed_strokes : open_strokes).push_back(p);
  }
  ClipperLib::ClipperOffset sweep(2.0, 0.25 * 1000);
  sweep.AddPaths(open_strokes, ClipperLib::jtRound, ClipperLib::etOpenRound);
  sweep.AddPaths(closed_strokes, ClipperLib::jtRound, ClipperLib::etClosedLine);
  ClipperLib::PolyTree drawn;
  sweep.Execute(drawn, radius_nm);

  Paths loops;
  int stray = 0;
  IntPoint first_stray;
  // Depth 0: the outside of a group of strokes; 1: a face inside it (board); 2: strokes
  // inside that face; 3: a face inside those (a cut-out); and so on.
  std::vector<std::pair<const ClipperLib::PolyNode*, int>> todo;
  for (const ClipperLib::PolyNode* n : drawn.Childs) todo.push_back({n, 0});
  while (!todo.empty()) {
    const auto [node, depth] = todo.back();
    todo.pop_back();
    if (node->IsHole()) {
      add_face(node->Contour, radius_nm, (depth / 2) % 2 == 0, loops);
    } else if (node->Childs.empty()) {
      if (stray++ == 0) first_stray = node->Contour.front();
    }
    for (const ClipperLib::PolyNode* c : node->Childs) todo.push_back({c, depth + 1});
  }
  const double tol_mm = 2 * radius_nm / kNmPerMm;
  if (loops.empty()) {
    std::ostringstream e;
    e << outline.path << ": the board outline does not close";
    IntPoint end;
    if (open_chain_end(strokes, 2 * radius_nm, end)) {
      e << ": a stroke chain ends at (" << to_mm(end).x() << ", " << to_mm(end).y()
        << ") mm, nothing continues it within " << tol_mm << " mm";
    } else {
      e << ": its strokes enclose no area";
    }
    throw CutoutError(e.str());
  }
  if (stray > 0 && notes) {
    std::ostringstream n;
    n << outline.path << ": warning: " << stray
      << " group(s) of outline strokes enclose nothing (first near " << mm_point(first_stray)
      << "): left out of the cut-out";
    notes->push_back(n.str());
  }
  return loops;
}

CutoutPlan plan_cutout(const PcbLayer& outline, const CutoutOptions& o) {
  if (!(o.cutter_diameter_mm > 0)) throw CutoutError("the cutter diameter must be positive");
  CutoutPlan plan;
  const Paths loops = outline_loops(outline, o.join_tolerance_mm, &plan.notes);
  if (loops.empty()) throw CutoutError(outline.path + ": the outline layer has no closed loop");
  // Boards positive, cut-outs negative: faces side by side (a T-junction) make one board.
  ClipperLib::Clipper c;
  c.AddPaths(loops, ClipperLib::ptSubject, true);
  c.Execute(ClipperLib::ctUnion, plan.board_nm, ClipperLib::pftPositive, ClipperLib::pftPositive);
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
