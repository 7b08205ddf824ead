// Isolation contours and narrow-gap detection (see isolation.h).
#include "host/lib/pcb/isolation.h"

#include <algorithm>  // std::max, std::min, std::remove_if, std::sort
#include <cmath>      // std::ceil, std::fabs, std::hypot, std::llround, std::sqrt
#include <stdexcept>  // std::invalid_argument

#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb {

namespace {

// Intersections smaller than this (nm^2, a 0.1 um square) are numerical touching.
const double kMinOverlapAreaNm2 = 1e4;

// The point of segment a-b nearest to x, and its distance from x (nm).
struct Nearest {
  double distance = 1e300;
  double x = 0, y = 0;
};
Nearest nearest_on_segment(const IntPoint& x, const IntPoint& a, const IntPoint& b) {
  const double ax = static_cast<double>(a.X), ay = static_cast<double>(a.Y);
  const double dx = static_cast<double>(b.X) - ax, dy = static_cast<double>(b.Y) - ay;
  const double px = static_cast<double>(x.X) - ax, py = static_cast<double>(x.Y) - ay;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? (px * dx + py * dy) / l2 : 0;
  t = std::max(0.0, std::min(1.0, t));
  const double ex = px - t * dx, ey = py - t * dy;
  return Nearest{std::sqrt(ex * ex + ey * ey), ax + t * dx, ay + t * dy};
}

// An edge of a path (from a vertex to the next).
struct Edge {
  IntPoint p, q;
};

// The edges of a closed path that reach into a box, appended to out.
void add_edges_near(const Path& path, const BoxNm& box, std::vector<Edge>* out) {
  for (size_t k = 0; k < path.size(); ++k) {
    const IntPoint& p = path[k];
    const IntPoint& q = path[(k + 1) % path.size()];
    if (std::max(p.X, q.X) < box.min_x || std::min(p.X, q.X) > box.max_x ||
        std::max(p.Y, q.Y) < box.min_y || std::min(p.Y, q.Y) > box.max_y)
      continue;
    out->push_back(Edge{p, q});
  }
}

// The narrowest place between two islands near a box: their smallest vertex-to-edge
// distance (nm) and where it is. The closest points of two islands whose clearances overlap
// lie within the box, so only vertices inside it and edges that reach into it are compared
// (a board-wide net has thousands of edges). Where the gap is as narrow along a stretch
// (parallel tracks: to within kTieNm), the place is the middle of that stretch when the
// middle is itself that narrow and halfway across, else the shortest line's middle nearest
// to it.
struct Narrowest {
  double distance_nm = 1e300;
  PointNm at;
};
Narrowest narrowest_place(const Paths& a, const Paths& b, const BoxNm& near) {
  const double kTieNm = 1000;
  auto edges_near = [&](const Paths& paths) {
    std::vector<Edge> out;
    for (const Path& path : paths) add_edges_near(path, near, &out);
    return out;
  };
  auto distance_to = [](const IntPoint& x, const std::vector<Edge>& edges) {
    double d = 1e300;
    for (const Edge& e : edges) d = std::min(d, nearest_on_segment(x, e.p, e.q).distance);
    return d;
  };
  const std::vector<Edge> edges_a = edges_near(a), edges_b = edges_near(b);
  struct Candidate {
    double distance, x, y;  // a shortest line's length and middle
  };
  std::vector<Candidate> ties;
  size_t kept_until = 1024;
  Narrowest best;
  for (int pass = 0; pass < 2; ++pass) {
    const Paths& u = pass ? b : a;
    const std::vector<Edge>& v = pass ? edges_a : edges_b;
    for (const Path& pu : u) {
      for (const IntPoint& x : pu) {
        if (!near.contains(x)) continue;
        for (const Edge& e : v) {
          const Nearest n = nearest_on_segment(x, e.p, e.q);
          if (n.distance > best.distance_nm + kTieNm) continue;
          best.distance_nm = std::min(best.distance_nm, n.distance);
          ties.push_back(Candidate{n.distance, (static_cast<double>(x.X) + n.x) / 2,
                                   (static_cast<double>(x.Y) + n.y) / 2});
          if (ties.size() >= kept_until) {  // drop those a narrower place has passed
            ties.erase(std::remove_if(ties.begin(), ties.end(),
                                      [&](const Candidate& c) {
                                        return c.distance > best.distance_nm + kTieNm;
                                      }),
                       ties.end());
            kept_until = std::max<size_t>(1024, 2 * ties.size());
          }
        }
      }
    }
  }
  if (ties.empty()) return best;
  double sx = 0, sy = 0;
  size_t count = 0;
  for (const Candidate& c : ties) {
    if (c.distance > best.distance_nm + kTieNm) continue;
    sx += c.x, sy += c.y, ++count;
  }
  const IntPoint middle(std::llround(sx / static_cast<double>(count)),
                        std::llround(sy / static_cast<double>(count)));
  const double to_a = distance_to(middle, edges_a), to_b = distance_to(middle, edges_b);
  if (to_a + to_b <= best.distance_nm + 2 * kTieNm && std::fabs(to_a - to_b) <= 2 * kTieNm) {
    best.at.x = middle.X;
    best.at.y = middle.Y;
    return best;
  }
  double nearest = 1e300;
  for (const Candidate& c : ties) {
    if (c.distance > best.distance_nm + kTieNm) continue;
    const double d =
        std::hypot(c.x - static_cast<double>(middle.X), c.y - static_cast<double>(middle.Y));
    if (d >= nearest) continue;
    nearest = d;
    best.at.x = std::llround(c.x);
    best.at.y = std::llround(c.y);
  }
  return best;
}

// Open path (closed contour with its first vertex repeated) for clipping.
Path as_open(const Path& p) {
  Path q = p;
  if (!q.empty()) q.push_back(q.front());
  return q;
}

// Open paths of `paths` (closed contours) that lie inside `area`.
Paths clip_to(const Paths& contours, const Paths& area) {
  ClipperLib::Clipper c;
  for (const Path& p : contours) c.AddPath(as_open(p), ClipperLib::ptSubject, false);
  c.AddPaths(area, ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  Paths out;
  ClipperLib::OpenPathsFromPolyTree(tree, out);
  return out;
}

// The islands without their empty holes (see IsolationOptions::isolate_empty_holes).
std::vector<Island> without_empty_holes(const std::vector<Island>& islands, size_t* skipped) {
  std::vector<Island> out;
  out.reserve(islands.size());
  for (const Island& island : islands) {
    Island kept;
    kept.box = island.box;
    size_t next_empty = 0;
    for (size_t k = 0; k < island.paths.size(); ++k) {
      if (next_empty < island.empty_holes.size() && island.empty_holes[next_empty] == k) {
        ++next_empty;
        ++*skipped;
        continue;
      }
      kept.paths.push_back(island.paths[k]);
    }
    out.push_back(std::move(kept));
  }
  return out;
}

}  // namespace

double clearing_edge_distance_mm(const IsolationOptions& o) {
  if (!(o.clearing_tool_width_mm > 0) || o.narrow_passes >= o.passes) return 0;
  const double step = o.tool_width_mm * (1.0 - o.overlap);
  const double narrow_outer = o.clearance_mm + o.tool_width_mm + (o.narrow_passes - 1) * step;
  return narrow_outer - o.overlap * o.tool_width_mm;
}

namespace {

// Whether two islands' outer boundaries stay at least apart_nm apart near a box (vertex to
// edge both ways: the boundaries of two islands never cross), neither island inside the
// other's outer boundary. Then their outers grown by half that cannot overlap in the box
// (each grown outline lies within the growth of its island). False when the edges near the
// box are too many to compare cheaply.
bool outers_apart(const Island& a, const Island& b, const BoxNm& near, double apart_nm) {
  if (a.box.contains(b.box) && ClipperLib::PointInPolygon(b.paths[0][0], a.paths[0]) != 0)
    return false;
  if (b.box.contains(a.box) && ClipperLib::PointInPolygon(a.paths[0][0], b.paths[0]) != 0)
    return false;
  std::vector<Edge> ea, eb;
  add_edges_near(a.paths[0], near, &ea);
  add_edges_near(b.paths[0], near, &eb);
  if (ea.size() * eb.size() > 20000) return false;
  // Each edge's ends against the other's edges.
  auto apart = [&](const std::vector<Edge>& eu, const std::vector<Edge>& ev) {
    for (const Edge& u : eu) {
      for (const IntPoint& x : {u.p, u.q}) {
        for (const Edge& v : ev)
          if (nearest_on_segment(x, v.p, v.q).distance < apart_nm) return false;
      }
    }
    return true;
  };
  return apart(ea, eb) && apart(eb, ea);
}

}  // namespace

std::vector<NarrowGap> find_narrow_gaps(const std::vector<Island>& islands, double radius_nm,
                                        double arc_tolerance_nm) {
  // Each outer boundary grown by the radius, made only for the pairs whose outers come near
  // (most never do); its box is the outer's grown by the radius and Clipper's rounding.
  struct Grown {
    Paths paths;
    bool made = false;
    BoxNm box;
    size_t index;
  };
  std::vector<Grown> grown;
  const cInt box_margin = static_cast<cInt>(std::ceil(radius_nm)) + 1;
  for (size_t i = 0; i < islands.size(); ++i) {
    Grown g;
    g.box.add(islands[i].paths[0]);
    g.box.min_x -= box_margin, g.box.min_y -= box_margin;
    g.box.max_x += box_margin, g.box.max_y += box_margin;
    g.index = i;
    grown.push_back(g);
  }
  auto grown_outer = [&](Grown& g) -> const Paths& {
    if (!g.made) {
      g.paths = offset_closed(Paths{islands[g.index].paths[0]}, radius_nm, arc_tolerance_nm);
      g.made = true;
    }
    return g.paths;
  };
  std::sort(grown.begin(), grown.end(),
            [](const Grown& a, const Grown& b) { return a.box.min_x < b.box.min_x; });
  // An island with its holes grown, seen through a box: only copper within 2r of the box can
  // grow into it, so the island is cut to the widened box first (a board-wide net with
  // thousands of holes would otherwise be offset whole), then the result to the box.
  auto grown_full_in = [&](size_t i, const BoxNm& box) {
    BoxNm wide = box;
    const cInt margin = static_cast<cInt>(2 * radius_nm + 2 * arc_tolerance_nm) + 1;
    wide.min_x -= margin, wide.min_y -= margin, wide.max_x += margin, wide.max_y += margin;
    return clip_to_box(
        offset_closed(clip_to_box(islands[i].paths, wide), radius_nm, arc_tolerance_nm), box);
  };
  std::vector<NarrowGap> gaps;
  for (size_t i = 0; i < grown.size(); ++i) {
    for (size_t j = i + 1; j < grown.size() && grown[j].box.min_x <= grown[i].box.max_x; ++j) {
      if (!grown[i].box.overlaps(grown[j].box)) continue;
      const Island& a = islands[grown[i].index];
      const Island& b = islands[grown[j].index];
      // Outer boundaries first: far apart near the common box (no Clipper intersection; jj
      // -5 %), else the grown ones' overlap (already grown); then with the holes, so an island
      // inside another's hole is checked against that hole. All only within the boxes'
      // common part: a board-wide net would otherwise make every pair a sweep over all of
      // its edges (two thirds of a dense board's isolation time).
      const BoxNm common = common_box(grown[i].box, grown[j].box);
      BoxNm reach = common;
      const cInt r = static_cast<cInt>(std::ceil(radius_nm)) + 1;
      reach.min_x -= r, reach.min_y -= r, reach.max_x += r, reach.max_y += r;
      // 2 nm more: Clipper rounds the grown vertices to the nanometre.
      if (outers_apart(a, b, reach, 2 * radius_nm + 2)) continue;
      if (std::fabs(signed_area(intersection_of(clip_to_box(grown_outer(grown[i]), common),
                                                clip_to_box(grown_outer(grown[j]), common)))) <
          kMinOverlapAreaNm2)
        continue;
      const Paths both = intersection_of(grown_full_in(grown[i].index, common),
                                         grown_full_in(grown[j].index, common));
      if (std::fabs(signed_area(both)) < kMinOverlapAreaNm2) continue;
      BoxNm near = box_of(both);
      const cInt grow = static_cast<cInt>(2 * radius_nm);
      near.min_x -= grow, near.min_y -= grow, near.max_x += grow, near.max_y += grow;
      // At the narrowest place (the middle of the region both clearances cover is outside
      // it for a gap round a corner, and at a pad's centre for a pad in a pour's opening).
      const Narrowest place = narrowest_place(a.paths, b.paths, near);
      NarrowGap g;
      g.at = place.at;
      g.gap_mm = place.distance_nm / kNmPerMm;
      g.island_a = std::min(grown[i].index, grown[j].index);
      g.island_b = std::max(grown[i].index, grown[j].index);
      gaps.push_back(g);
    }
  }
  std::sort(gaps.begin(), gaps.end(), [](const NarrowGap& a, const NarrowGap& b) {
    return a.island_a != b.island_a ? a.island_a < b.island_a : a.island_b < b.island_b;
  });
  return gaps;
}

namespace {

// The tool centre's distances: from the copper, between passes, and Clipper's arc tolerance.
struct PassGeometry {
  double radius_nm = 0, step_nm = 0, arc_tol_nm = 0;
};

void add_tool_paths(const Paths& paths, int pass, bool closed, bool clearing, IsolationResult* r) {
  for (const Path& p : paths) {
    ToolPathNm t;
    t.path = p;
    t.pass = pass;
    t.closed = closed;
    t.clearing = clearing;
    r->paths.push_back(t);
  }
}

void check_isolation_options(const IsolationOptions& o) {
  if (!(o.tool_width_mm > 0)) throw std::invalid_argument("the tool width must be positive");
  if (o.passes < 1) throw std::invalid_argument("at least one isolation pass is needed");
  if (!(o.clearance_mm >= 0 && o.clearance_mm <= 1))
    throw std::invalid_argument("the isolation clearance must be between 0 and 1 mm");
  if (!(o.overlap >= 0 && o.overlap <= 0.9))
    throw std::invalid_argument("the pass overlap must be between 0 and 0.9");
}

// The narrow tool's first passes, then the clearing tool out to the edge `passes` narrow
// passes would reach: its inner edge at edge_mm, passes overlapping by the overlap.
void plan_with_clearing_tool(const std::vector<Island>& islands, const IsolationOptions& o,
                             const PassGeometry& g, double edge_mm, IsolationResult* r) {
  const double radius_nm = g.radius_nm, step_nm = g.step_nm, arc_tol_nm = g.arc_tol_nm;
  for (int k = 0; k < o.narrow_passes; ++k) {
    add_tool_paths(grown_islands(islands, radius_nm + k * step_nm, arc_tol_nm), k, true, false, r);
  }
  const double wide_mm = o.clearing_tool_width_mm;
  const double outer_mm =
      o.clearance_mm + o.tool_width_mm + (o.passes - 1) * o.tool_width_mm * (1.0 - o.overlap);
  const double wide_step_mm = wide_mm * (1.0 - o.overlap);
  const int wide_passes =
      1 + std::max(
              0, static_cast<int>(std::ceil((outer_mm - edge_mm - wide_mm) / wide_step_mm - 1e-9)));
  r->clearing_tool_radius_mm = wide_mm / 2;
  for (int k = 0; k < wide_passes; ++k) {
    const double centre_mm = edge_mm + wide_mm / 2 + k * wide_step_mm;
    add_tool_paths(grown_islands(islands, centre_mm * kNmPerMm, arc_tol_nm), o.narrow_passes + k,
                   true, true, r);
  }
  // Where the wide tool cannot reach (into an acute corner between tracks), the narrow
  // tool's further passes clear what is left of the band, clipped to that part.
  Paths centres;
  Paths wide_centres;
  for (const ToolPathNm& t : r->paths)
    (t.clearing ? wide_centres : centres).push_back(t.closed ? as_open(t.path) : t.path);
  Paths swept = sweep_open(centres, radius_nm - o.clearance_mm * kNmPerMm, arc_tol_nm);
  const Paths wide_swept = sweep_open(wide_centres, wide_mm / 2 * kNmPerMm, arc_tol_nm);
  swept.insert(swept.end(), wide_swept.begin(), wide_swept.end());
  const Paths band = difference_of(grown_islands(islands, outer_mm * kNmPerMm, arc_tol_nm),
                                   grown_islands(islands, o.clearance_mm * kNmPerMm, arc_tol_nm));
  const Paths left = difference_of(band, union_of(swept));
  if (std::fabs(signed_area(left)) >= kMinOverlapAreaNm2) {
    const Paths near_left = offset_closed(left, o.tool_width_mm * kNmPerMm, arc_tol_nm);
    for (int k = o.narrow_passes; k < o.passes; ++k) {
      add_tool_paths(
          clip_to(grown_islands(islands, radius_nm + k * step_nm, arc_tol_nm), near_left), k, false,
          false, r);
    }
  }
  std::stable_sort(r->paths.begin(), r->paths.end(), [](const ToolPathNm& a, const ToolPathNm& b) {
    return !a.clearing && b.clearing;
  });
}

// Contours around each island, `passes` of them.
void plan_contours(const std::vector<Island>& islands, const IsolationOptions& o,
                   const PassGeometry& g, IsolationResult* r) {
  const double radius_nm = g.radius_nm, step_nm = g.step_nm, arc_tol_nm = g.arc_tol_nm;
  const std::vector<Island> cut =
      o.isolate_empty_holes ? islands : without_empty_holes(islands, &r->empty_holes_skipped);
  for (int k = 0; k < o.passes; ++k) {
    add_tool_paths(grown_islands(cut, radius_nm + k * step_nm, arc_tol_nm), k, true, false, r);
  }
}

// One stroke along a piece's principal axis (of its vertices), end to end.
Path principal_axis_stroke(const Path& piece) {
  double mx = 0, my = 0;
  for (const IntPoint& q : piece) mx += static_cast<double>(q.X), my += static_cast<double>(q.Y);
  mx /= static_cast<double>(piece.size()), my /= static_cast<double>(piece.size());
  double sxx = 0, syy = 0, sxy = 0;
  for (const IntPoint& q : piece) {
    const double dx = static_cast<double>(q.X) - mx, dy = static_cast<double>(q.Y) - my;
    sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  const double ux = std::cos(angle), uy = std::sin(angle);
  double lo = 0, hi = 0;
  for (const IntPoint& q : piece) {
    const double t = (static_cast<double>(q.X) - mx) * ux + (static_cast<double>(q.Y) - my) * uy;
    lo = std::min(lo, t), hi = std::max(hi, t);
  }
  return Path{IntPoint(static_cast<cInt>(mx + lo * ux), static_cast<cInt>(my + lo * uy)),
              IntPoint(static_cast<cInt>(mx + hi * ux), static_cast<cInt>(my + hi * uy))};
}

// Where the fronts of two islands meet, cusps wider than the step stay uncut: one short
// stroke along each leftover sliver's long axis, kept where the tool centre may go.
void add_cusp_strokes(const std::vector<Island>& islands, const Paths& centre_area, int last_pass,
                      const PassGeometry& g, IsolationResult* r) {
  const double radius_nm = g.radius_nm, arc_tol_nm = g.arc_tol_nm;
  const Paths allowed = difference_of(centre_area, grown_islands(islands, radius_nm, arc_tol_nm));
  const Paths reachable = offset_closed(allowed, radius_nm, arc_tol_nm);
  for (int round = 0; round < 3; ++round) {
    Paths centres;
    for (const ToolPathNm& t : r->paths) centres.push_back(t.closed ? as_open(t.path) : t.path);
    const Paths left = difference_of(reachable, sweep_open(centres, radius_nm, arc_tol_nm));
    Paths strokes;
    for (const Path& piece : left) {
      if (ClipperLib::Area(piece) < kMinOverlapAreaNm2 * 100) continue;  // slivers < 1 um^2
      strokes.push_back(principal_axis_stroke(piece));
    }
    if (strokes.empty()) break;
    ClipperLib::Clipper c;
    c.AddPaths(strokes, ClipperLib::ptSubject, false);
    c.AddPaths(allowed, ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    c.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    Paths kept;
    ClipperLib::OpenPathsFromPolyTree(tree, kept);
    if (kept.empty()) break;
    add_tool_paths(kept, last_pass + 1 + round, false, false, r);
  }
}

// Clearing: contours grow until the area (shrunk by the tool radius, where the tool centre
// may go) is covered; the area's own inset boundary is the last contour.
void plan_mill_all(const std::vector<Island>& islands, const IsolationOptions& o,
                   const PassGeometry& g, IsolationResult* r) {
  const double radius_nm = g.radius_nm, step_nm = g.step_nm, arc_tol_nm = g.arc_tol_nm;
  Paths area = o.area_nm;
  if (area.empty()) {
    BoxNm b;
    for (const Island& island : islands) b.add(island.paths[0]);
    const cInt m = static_cast<cInt>(4 * radius_nm);
    area.push_back(Path{IntPoint(b.min_x - m, b.min_y - m), IntPoint(b.max_x + m, b.min_y - m),
                        IntPoint(b.max_x + m, b.max_y + m), IntPoint(b.min_x - m, b.max_y + m)});
  }
  const Paths centre_area = offset_closed(union_of(area), -radius_nm, arc_tol_nm);
  for (int k = 0; k < 100000; ++k) {
    const double d = radius_nm + k * step_nm;
    const Paths contours = grown_islands(islands, d, arc_tol_nm);
    if (k == 0) {
      add_tool_paths(contours, 0, true, false, r);
    } else {
      add_tool_paths(clip_to(contours, centre_area), k, false, false, r);
    }
    const Paths left = difference_of(centre_area, grown_islands(islands, d + step_nm, arc_tol_nm));
    if (std::fabs(signed_area(left)) < kMinOverlapAreaNm2) break;
  }
  const int last_pass = r->paths.empty() ? 1 : r->paths.back().pass + 1;
  add_tool_paths(centre_area, last_pass, true, false, r);
  add_cusp_strokes(islands, centre_area, last_pass, g, r);
}

}  // namespace

IsolationResult plan_isolation(const Paths& copper_in, const IsolationOptions& o) {
  check_isolation_options(o);
  return plan_isolation(copper_islands(copper_in), o);
}

IsolationResult plan_isolation(const std::vector<Island>& islands, const IsolationOptions& o) {
  check_isolation_options(o);
  IsolationResult r;
  // The tool centre's distance from the copper (r.tool_radius_mm stays the tool's own).
  const double radius_nm = (o.tool_width_mm / 2 + o.clearance_mm) * kNmPerMm;
  const double step_nm = o.tool_width_mm * kNmPerMm * (1.0 - o.overlap);
  const double arc_tol_nm = o.arc_tolerance_mm * kNmPerMm;
  r.tool_radius_mm = o.tool_width_mm / 2;
  r.islands = islands.size();
  r.narrow_gaps = find_narrow_gaps(islands, radius_nm + kNarrowGapRoomNm / 2, arc_tol_nm);
  if (islands.empty()) return r;

  if (o.clearing_tool_width_mm > 0) {
    if (!(o.clearing_tool_width_mm > o.tool_width_mm))
      throw std::invalid_argument("the clearing tool must be wider than the isolation tool");
    if (o.mill_all) throw std::invalid_argument("a clearing tool cannot be combined with mill-all");
    if (o.narrow_passes < 1)
      throw std::invalid_argument("at least one pass of the isolation tool is needed");
  }
  const double edge_mm = clearing_edge_distance_mm(o);
  const PassGeometry g{radius_nm, step_nm, arc_tol_nm};
  if (!o.mill_all && edge_mm > 0) {
    plan_with_clearing_tool(islands, o, g, edge_mm, &r);
  } else if (!o.mill_all) {
    plan_contours(islands, o, g, &r);
  } else {
    plan_mill_all(islands, o, g, &r);
  }
  return r;
}

}  // namespace host::pcb
