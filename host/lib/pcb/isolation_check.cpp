// The isolation checks (see isolation_check.h).
#include "host/lib/pcb/isolation_check.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::max, std::sort
#include <cmath>      // std::fabs, std::sqrt
#include <map>        // std::map

#include "host/lib/pcb/near_copper.h"
#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/pcb/standing_pieces.h"
#include "host/lib/plan/counted.h"  // counted: "1 hole", "2 holes"

namespace host::pcb {

namespace {

const double kArcToleranceNm = 200;  // flattening of the swept discs
const double kMinHitAreaNm2 = 1e4;   // 0.1 um x 0.1 um: numerical touching

// A point strictly inside the region (even-odd over all paths): the middle of the widest
// interval a horizontal line through the region's vertical middle cuts out of it.
bool interior_point(const Paths& region, IntPoint* out) {
  const BoxNm b = box_of(region);
  if (b.empty()) return false;
  // Try a few scan lines: a line through a vertex is nudged by half a nanometre.
  for (int attempt = 1; attempt < 8; ++attempt) {
    const double y =
        static_cast<double>(b.min_y) + static_cast<double>(b.max_y - b.min_y) * attempt / 8.0 + 0.5;
    std::vector<double> xs;
    for (const Path& p : region) {
      for (size_t i = 0; i < p.size(); ++i) {
        const IntPoint& u = p[i];
        const IntPoint& v = p[(i + 1) % p.size()];
        const double uy = static_cast<double>(u.Y), vy = static_cast<double>(v.Y);
        if ((uy <= y) == (vy <= y)) continue;
        const double t = (y - uy) / (vy - uy);
        xs.push_back(static_cast<double>(u.X) + t * static_cast<double>(v.X - u.X));
      }
    }
    std::sort(xs.begin(), xs.end());
    double best = 0;
    for (size_t i = 0; i + 1 < xs.size(); i += 2) {
      if (xs[i + 1] - xs[i] > best) {
        best = xs[i + 1] - xs[i];
        out->X = static_cast<cInt>((xs[i] + xs[i + 1]) / 2);
        out->Y = static_cast<cInt>(y);
      }
    }
    if (best > 2) return true;
  }
  return false;
}

// The path with the vertices left out that lie within near_nm of the line between the kept
// ones around them (checked for every vertex left out since the last kept, at most kRun of
// them). A simulated run samples every millisecond: straight runs are thousands of nearly
// collinear points that made the sweep and the unions take minutes on a large board.
Path without_collinear(const Path& p, double near_nm) {
  const size_t kRun = 64;
  if (p.size() < 3) return p;
  Path out{p.front()};
  size_t first_skipped = 1;
  for (size_t i = 1; i + 1 < p.size(); ++i) {
    // Would dropping p[first_skipped .. i] keep them all near out.back() -> p[i + 1]?
    const IntPoint& a = out.back();
    const IntPoint& b = p[i + 1];
    const double dx = static_cast<double>(b.X - a.X), dy = static_cast<double>(b.Y - a.Y);
    const double len2 = dx * dx + dy * dy, len = std::sqrt(len2);
    const double near_cross = near_nm * len;  // |cross| / len <= near_nm, without a division
    bool ok = len > 0 && i + 1 - first_skipped <= kRun;
    for (size_t k = first_skipped; ok && k <= i; ++k) {
      const double ex = static_cast<double>(p[k].X - a.X), ey = static_cast<double>(p[k].Y - a.Y);
      const double along = ex * dx + ey * dy;
      ok = along >= 0 && along <= len2 && std::fabs(ex * dy - ey * dx) <= near_cross;
    }
    if (!ok) {
      out.push_back(p[i]);
      first_skipped = i + 1;
    }
  }
  out.push_back(p.back());
  return out;
}

// The tool-centre paths in nanometres, a lone point as a zero-length run.
Paths centre_paths(const std::vector<std::vector<Point2>>& tool_paths_mm, double tolerance_mm) {
  Paths centres;
  for (const std::vector<Point2>& path : tool_paths_mm) {
    Path p;
    for (const Point2& q : path) p.emplace_back(nm_from_mm(q.x()), nm_from_mm(q.y()));
    if (p.size() == 1) p.push_back(p.front());
    // Thinned to a tenth of the tolerance: the verdicts move by at most that much, and a
    // simulated path (the tool wanders by a few hundred nanometres) keeps half the vertices
    // it kept at 50 nm (A64-OlinuXino top: 0.79 -> 0.36 million; check 63 -> 31 s).
    if (!p.empty()) centres.push_back(without_collinear(p, tolerance_mm * kNmPerMm / 10));
  }
  return centres;
}

// 1. The tool, shrunk by the tolerance, must not reach copper.
// near_runs: the centres' runs within the full radius of copper (runs_near_copper), which
// hold every run within the shrunk radius.
void find_copper_hits(const std::vector<Island>& islands, const Paths& copper,
                      const Paths& near_runs, double tool_radius_mm, double tolerance_mm,
                      IsolationCheck* r) {
  const double shrunk = (tool_radius_mm - tolerance_mm) * kNmPerMm;
  if (!(shrunk > 0) || near_runs.empty()) return;
  // Copper AND the union of the sweeps is the union, strip by strip, of the copper near a
  // strip AND that strip's sweep: the whole job's sweep is never united in one piece (on
  // A64-OlinuXino, top, 0.2 mm: 3.3 -> 1.9 s of the check).
  // Only the centres' runs that come within the shrunk radius of copper (or run inside
  // it) can cut it: the others are never swept (A64-OlinuXino top, 0.2 mm: none, and the
  // check 7 -> 4 s).
  std::vector<Paths> pieces;
  for (const Path& p : runs_near_copper(near_runs, copper, shrunk)) pieces.push_back(Paths{p});
  const Paths cut_copper = united_by_strips(pieces, [&](const Paths& group) {
    const Paths swept_in = sweep_open(group, shrunk, kArcToleranceNm);
    const BoxNm near = box_of(swept_in);
    Paths copper_near;
    for (const Island& island : islands) {
      if (!island.box.overlaps(near)) continue;
      const Paths part = near.contains(island.box) ? island.paths : clip_to_box(island.paths, near);
      copper_near.insert(copper_near.end(), part.begin(), part.end());
    }
    return intersection_of(copper_near, swept_in);
  });
  ClipperLib::Clipper c;
  c.AddPaths(cut_copper, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  for (const StandingPiece& p : pieces_of(tree)) {
    Paths region{p.outer};
    region.insert(region.end(), p.holes.begin(), p.holes.end());
    const double a = std::fabs(signed_area(region));
    if (a < kMinHitAreaNm2) continue;
    CopperHit h;
    h.at_mm = to_mm(centroid(region));
    h.area_mm2 = a / (kNmPerMm * kNmPerMm);
    r->hits.push_back(h);
  }
}

// Which standing piece holds each island (by a point of the island the tool leaves standing,
// inner[i]).
void locate_islands(const std::vector<Island>& islands, const Paths& swept,
                    const std::vector<StandingPiece>& pieces,
                    std::map<size_t, std::vector<size_t>>* by_whole, std::vector<IntPoint>* inner) {
  std::vector<BoxNm> swept_boxes(swept.size());
  for (size_t k = 0; k < swept.size(); ++k) swept_boxes[k].add(swept[k]);
  for (size_t i = 0; i < islands.size(); ++i) {
    // A point of the island the tool leaves standing (the island is otherwise all cut away,
    // which the first check reports).
    // Only the swept area over the island's box matters: cut to it first (linear), or every
    // island's difference sweeps the whole job (A64-OlinuXino: 1 133 islands, minutes); and
    // only the swept paths whose boxes reach it (a thin tool's sweep is a band per contour).
    Paths near;
    for (size_t k = 0; k < swept.size(); ++k) {
      if (swept_boxes[k].overlaps(islands[i].box)) near.push_back(swept[k]);
    }
    const Paths left = near.empty()
                           ? islands[i].paths
                           : difference_of(islands[i].paths, clip_to_box(near, islands[i].box));
    if (!interior_point(left, &(*inner)[i])) continue;
    for (const StandingPiece& p : pieces) {
      if (!p.holds((*inner)[i])) continue;
      (*by_whole)[p.whole].push_back(i);
      break;
    }
  }
}

// 2. Material left standing (everything minus the full swept tool) in connected pieces;
// each island must sit in a piece of its own.
void find_unseparated(const std::vector<Island>& islands, const Paths& copper, const Paths& centres,
                      const Paths& near_runs, double tool_radius_mm, IsolationCheck* r) {
  const double radius_nm = tool_radius_mm * kNmPerMm;
  BoxNm b = box_of(copper);
  if (b.empty()) return;
  const cInt m = static_cast<cInt>(4 * radius_nm + 1e6);
  BoxNm frame = b;
  frame.min_x -= m;
  frame.min_y -= m;
  frame.max_x += m;
  frame.max_y += m;
  const std::vector<StandingPiece> pieces = standing_pieces(
      frame, centres.empty() ? Paths{} : sweep_open_unjoined(centres, radius_nm, kArcToleranceNm));
  std::map<size_t, std::vector<size_t>> by_whole;
  std::vector<IntPoint> inner(islands.size());
  // What the tool leaves of an island is cut only by the centres' runs within its reach of
  // copper (the rest touch no copper): their sweep, far smaller than the whole job's.
  const Paths swept_near =
      near_runs.empty() ? Paths{} : sweep_open(near_runs, radius_nm, kArcToleranceNm);
  locate_islands(islands, swept_near, pieces, &by_whole, &inner);
  for (const auto& entry : by_whole) {
    const std::vector<size_t>& v = entry.second;
    for (size_t k = 1; k < v.size(); ++k) {
      UnseparatedPair u;
      u.island_a = v[0];
      u.island_b = v[k];
      u.a_mm = to_mm(inner[v[0]]);
      u.b_mm = to_mm(inner[v[k]]);
      r->unseparated.push_back(u);
    }
  }
}

}  // namespace

IsolationCheck check_isolation(const Paths& copper_nm,
                               const std::vector<std::vector<Point2>>& tool_paths_mm,
                               double tool_radius_mm, double tolerance_mm) {
  return check_isolation(copper_islands(copper_nm), tool_paths_mm, tool_radius_mm, tolerance_mm);
}

IsolationCheck check_isolation(const std::vector<Island>& islands,
                               const std::vector<std::vector<Point2>>& tool_paths_mm,
                               double tool_radius_mm, double tolerance_mm) {
  IsolationCheck r;
  r.islands = islands.size();
  const Paths centres = centre_paths(tool_paths_mm, tolerance_mm);
  // The islands are the union's pieces: their paths together are the union (a second union
  // would sweep the whole board again).
  const Paths copper = copper_paths(islands);

  // Only the runs within the tool's reach of copper can cut it (the rest are never swept
  // for hits) or take part of an island away.
  const double reach_mm = std::max(tool_radius_mm, tool_radius_mm - tolerance_mm);
  const Paths near_runs = runs_near_copper(centres, copper, reach_mm * kNmPerMm);
  find_copper_hits(islands, copper, near_runs, tool_radius_mm, tolerance_mm, &r);
  find_unseparated(islands, copper, centres, near_runs, tool_radius_mm, &r);
  return r;
}

std::string describe(const IsolationCheck& c) {
  std::string s =
      fmt::format("{}, {}, {}", counted(c.islands, "island"), counted(c.hits.size(), "copper hit"),
                  counted(c.unseparated.size(), "unseparated pair"));
  // The largest hits first, at most kListed of each kind: a job with thousands (a board run
  // without clearance) gave as many lines.
  const size_t kListed = 20;
  std::vector<CopperHit> hits = c.hits;
  std::sort(hits.begin(), hits.end(),
            [](const CopperHit& a, const CopperHit& b) { return a.area_mm2 > b.area_mm2; });
  for (size_t i = 0; i < hits.size() && i < kListed; ++i) {
    s += fmt::format("\n  tool cuts {:.6f} mm2 of copper at ({:.3f}, {:.3f}) mm on the machine",
                     hits[i].area_mm2, hits[i].at_mm.x(), hits[i].at_mm.y());
  }
  if (hits.size() > kListed) s += fmt::format("\n  ... and {} smaller", hits.size() - kListed);
  for (size_t i = 0; i < c.unseparated.size() && i < kListed; ++i) {
    const UnseparatedPair& u = c.unseparated[i];
    s += fmt::format(
        "\n  islands {} at ({:.3f}, {:.3f}) and {} at ({:.3f}, {:.3f}) mm on the machine are "
        "not separated by a cut",
        u.island_a, u.a_mm.x(), u.a_mm.y(), u.island_b, u.b_mm.x(), u.b_mm.y());
  }
  if (c.unseparated.size() > kListed)
    s += fmt::format("\n  ... and {} more pairs", c.unseparated.size() - kListed);
  return s;
}

}  // namespace host::pcb
