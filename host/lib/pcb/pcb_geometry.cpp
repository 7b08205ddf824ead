// Geometry helpers for the PCB planners (see pcb_geometry.h).
#include "host/lib/pcb/pcb_geometry.h"

#include <algorithm>   // std::min, std::max, std::sort
#include <cmath>       // std::llround, std::fabs
#include <functional>  // std::function
#include <iterator>    // std::make_move_iterator
#include <utility>     // std::move

#include "host/lib/pcb/disc_outline.h"

namespace host::pcb {

using ClipperLib::Clipper;
using ClipperLib::ClipperOffset;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;
using ClipperLib::PolyNode;
using ClipperLib::PolyTree;

void BoxNm::add(const IntPoint& p) {
  if (empty()) {
    min_x = max_x = p.X;
    min_y = max_y = p.Y;
    return;
  }
  min_x = std::min(min_x, p.X);
  max_x = std::max(max_x, p.X);
  min_y = std::min(min_y, p.Y);
  max_y = std::max(max_y, p.Y);
}

void BoxNm::add(const Path& path) {
  for (const IntPoint& p : path) add(p);
}

size_t root_of(std::vector<size_t>* parent, size_t k) {
  while ((*parent)[k] != k) {
    (*parent)[k] = (*parent)[(*parent)[k]];
    k = (*parent)[k];
  }
  return k;
}

BoxNm box_of(const Paths& paths) {
  BoxNm b;
  for (const Path& p : paths) b.add(p);
  return b;
}

BoxNm common_box(const BoxNm& a, const BoxNm& b) {
  BoxNm r;
  if (!a.overlaps(b)) return r;
  r.min_x = std::max(a.min_x, b.min_x);
  r.min_y = std::max(a.min_y, b.min_y);
  r.max_x = std::min(a.max_x, b.max_x);
  r.max_y = std::min(a.max_y, b.max_y);
  return r;
}

namespace {

// One Sutherland-Hodgman stage: keep the side of the line `axis = limit` where
// inside(p) holds; crossing points are rounded to the nanometre.
template <typename Inside>
Path clip_stage(const Path& in, bool x_axis, ClipperLib::cInt limit, Inside inside) {
  Path out;
  if (in.empty()) return out;
  out.reserve(in.size() + 4);
  IntPoint prev = in.back();
  bool prev_in = inside(prev);
  for (const IntPoint& cur : in) {
    const bool cur_in = inside(cur);
    if (cur_in != prev_in) {
      const double a = x_axis ? static_cast<double>(prev.X) : static_cast<double>(prev.Y);
      const double b = x_axis ? static_cast<double>(cur.X) : static_cast<double>(cur.Y);
      const double t = (static_cast<double>(limit) - a) / (b - a);
      const double ox = static_cast<double>(prev.X), oy = static_cast<double>(prev.Y);
      const double u = ox + t * (static_cast<double>(cur.X) - ox);
      const double v = oy + t * (static_cast<double>(cur.Y) - oy);
      out.push_back(x_axis ? IntPoint(limit, std::llround(v)) : IntPoint(std::llround(u), limit));
    }
    if (cur_in) out.push_back(cur);
    prev = cur;
    prev_in = cur_in;
  }
  return out;
}

}  // namespace

void clip_path_to_box(const Path& p, const BoxNm& p_box, const BoxNm& box, Paths* out) {
  if (box.empty() || !p_box.overlaps(box)) return;
  if (box.contains(p_box)) {
    out->push_back(p);  // wholly inside
    return;
  }
  Path q = clip_stage(p, true, box.min_x, [&](const IntPoint& v) { return v.X >= box.min_x; });
  q = clip_stage(q, true, box.max_x, [&](const IntPoint& v) { return v.X <= box.max_x; });
  q = clip_stage(q, false, box.min_y, [&](const IntPoint& v) { return v.Y >= box.min_y; });
  q = clip_stage(q, false, box.max_y, [&](const IntPoint& v) { return v.Y <= box.max_y; });
  if (q.size() >= 3) out->push_back(std::move(q));
}

Paths clip_to_box(const Paths& paths, const BoxNm& box) {
  Paths out;
  for (const Path& p : paths) {
    BoxNm pb;
    pb.add(p);
    clip_path_to_box(p, pb, box, &out);
  }
  return out;
}

Paths union_of(const Paths& paths) {
  Clipper c;
  c.AddPaths(paths, ClipperLib::ptSubject, true);
  Paths out;
  c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

namespace {

// Outer nodes of the tree (depth 0, 2, 4, ...) become islands with their direct holes.
void collect_islands(const PolyNode& node, std::vector<Island>* out) {
  for (const PolyNode* outer : node.Childs) {
    Island island;
    island.paths.push_back(outer->Contour);
    for (const PolyNode* hole : outer->Childs) {
      if (hole->Childs.empty()) island.empty_holes.push_back(island.paths.size());
      island.paths.push_back(hole->Contour);
      collect_islands(*hole, out);
    }
    island.box.add(outer->Contour);
    out->push_back(island);
  }
}

}  // namespace

std::vector<Island> copper_islands(const Paths& copper) {
  Clipper c;
  c.AddPaths(copper, ClipperLib::ptSubject, true);
  PolyTree tree;
  c.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  std::vector<Island> out;
  collect_islands(tree, &out);
  return out;
}

Paths copper_paths(const std::vector<Island>& islands) {
  Paths out;
  for (const Island& island : islands)
    out.insert(out.end(), island.paths.begin(), island.paths.end());
  return out;
}

double signed_area(const Paths& paths) {
  double a = 0;
  for (const Path& p : paths) a += ClipperLib::Area(p);
  return a;
}

IntPoint centroid(const Paths& paths) {
  double a_sum = 0, x_sum = 0, y_sum = 0;
  for (const Path& p : paths) {
    for (size_t i = 0; i < p.size(); ++i) {
      const IntPoint& u = p[i];
      const IntPoint& v = p[(i + 1) % p.size()];
      const double cross = static_cast<double>(u.X) * static_cast<double>(v.Y) -
                           static_cast<double>(v.X) * static_cast<double>(u.Y);
      a_sum += cross;
      x_sum += (static_cast<double>(u.X) + static_cast<double>(v.X)) * cross;
      y_sum += (static_cast<double>(u.Y) + static_cast<double>(v.Y)) * cross;
    }
  }
  if (a_sum == 0) {
    for (const Path& p : paths)
      if (!p.empty()) return p[0];
    return IntPoint(0, 0);
  }
  return IntPoint(static_cast<ClipperLib::cInt>(x_sum / (3 * a_sum)),
                  static_cast<ClipperLib::cInt>(y_sum / (3 * a_sum)));
}

namespace {

// Input vertices per strip: a strip's round offset is one Clipper of several times as many
// edges, whose cost is its edges times those a scan line crosses in it (20 000: 11.7 MB on
// eaglecad1's check; 5 000: peak 29.6 -> 27.4 MB, 0.39 -> 0.30 s; 1 000: KNoT_Thing's
// `board` 0.13 -> 0.07 s, dan's 1.00 -> 0.92 s; 500 no faster).
const size_t kStripVertices = 1000;

size_t vertex_count(const Paths& paths) {
  size_t n = 0;
  for (const Path& p : paths) n += p.size();
  return n;
}

// ClipperOffset unites what it makes (positive fill): one call is one union.
Paths offset_together(const Paths& paths, double delta_nm, double arc_tolerance_nm,
                      ClipperLib::EndType end) {
  ClipperOffset o;
  o.ArcTolerance = arc_tolerance_nm;
  o.AddPaths(paths, ClipperLib::jtRound, end);
  Paths out;
  o.Execute(out, delta_nm);
  return out;
}

}  // namespace

// Clipper's union visits, at every scan beam, each edge that crosses it, so one union of a
// whole board's pieces is slow in the board's width (A64-OlinuXino, the check's sweep of a
// 0.2 mm tool: 12 s in one union, 2.4 s by strips).
namespace {

// united_by_strips without the last union: each strip's union.
std::vector<Paths> united_strips(const std::vector<Paths>& pieces,
                                 const std::function<Paths(const Paths&)>& united) {
  std::vector<std::pair<double, size_t>> by_x;  // box centre x, index
  by_x.reserve(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i) {
    const BoxNm b = box_of(pieces[i]);
    by_x.emplace_back(b.empty() ? 0.0 : (static_cast<double>(b.min_x) + b.max_x) / 2, i);
  }
  std::sort(by_x.begin(), by_x.end());
  std::vector<Paths> strips;
  Paths group;
  size_t in_group = 0;
  for (size_t k = 0; k < by_x.size(); ++k) {
    const Paths& piece = pieces[by_x[k].second];
    group.insert(group.end(), piece.begin(), piece.end());
    in_group += vertex_count(piece);
    if (in_group >= kStripVertices || k + 1 == by_x.size()) {
      strips.push_back(united(group));
      group.clear();
      in_group = 0;
    }
  }
  return strips;
}

// One polygon of a union's result: an outer path and its holes, and its box.
struct Polygon {
  Paths paths;  // the outer first
  BoxNm box;
  size_t strip;
};

// A union's result (outers positive, holes negative, in no order) as polygons: each hole
// goes with the smallest outer around it (an island in a hole is smaller than the outer
// whose hole it sits in).
void add_polygons(Paths&& result, size_t strip, std::vector<Polygon>* out) {
  const size_t first = out->size();
  std::vector<double> area;
  Paths holes;
  for (Path& p : result) {
    if (ClipperLib::Orientation(p)) {
      Polygon g;
      g.box.add(p);
      g.strip = strip;
      g.paths.push_back(std::move(p));
      out->push_back(std::move(g));
      area.push_back(std::fabs(ClipperLib::Area(out->back().paths[0])));
    } else {
      holes.push_back(std::move(p));
    }
  }
  for (Path& h : holes) {
    size_t best = out->size();
    for (size_t k = first; k < out->size(); ++k) {
      const Polygon& g = (*out)[k];
      if (!g.box.contains(h[0]) || (best < out->size() && area[k - first] >= area[best - first]))
        continue;
      if (ClipperLib::PointInPolygon(h[0], g.paths[0]) != 0) best = k;
    }
    if (best == out->size()) {  // not expected of a union: kept with the first polygon
      best = first;
      if (best == out->size()) continue;
    }
    (*out)[best].paths.push_back(std::move(h));
  }
}

// The strips' results as one union. Only the polygons that meet a polygon of another strip
// (by their boxes, touching included) go through a union again, each group of them on its
// own: one union of everything swept the whole board's width at every scan beam, and the
// strips' overlaps made it most of reading a Gerber file (eaglecad1: 20 of 32 ms).
Paths joined_strips(std::vector<Paths> strips) {
  std::vector<Polygon> polygons;
  for (size_t s = 0; s < strips.size(); ++s) add_polygons(std::move(strips[s]), s, &polygons);
  std::vector<size_t> by_x(polygons.size()), parent(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) by_x[i] = parent[i] = i;
  std::sort(by_x.begin(), by_x.end(),
            [&](size_t a, size_t b) { return polygons[a].box.min_x < polygons[b].box.min_x; });
  for (size_t i = 0; i < by_x.size(); ++i) {
    const Polygon& a = polygons[by_x[i]];
    for (size_t j = i + 1; j < by_x.size() && polygons[by_x[j]].box.min_x <= a.box.max_x; ++j) {
      const Polygon& b = polygons[by_x[j]];
      if (b.strip != a.strip && b.box.overlaps(a.box))
        parent[root_of(&parent, by_x[j])] = root_of(&parent, by_x[i]);
    }
  }
  std::vector<Paths> groups(polygons.size());
  std::vector<size_t> members(polygons.size(), 0);
  for (size_t i = 0; i < polygons.size(); ++i) {
    const size_t r = root_of(&parent, i);
    ++members[r];
    groups[r].insert(groups[r].end(), std::make_move_iterator(polygons[i].paths.begin()),
                     std::make_move_iterator(polygons[i].paths.end()));
  }
  Paths all;
  for (size_t r = 0; r < groups.size(); ++r) {
    if (members[r] == 0) continue;
    Paths joined = members[r] == 1 ? std::move(groups[r]) : union_of(groups[r]);
    all.insert(all.end(), std::make_move_iterator(joined.begin()),
               std::make_move_iterator(joined.end()));
  }
  return all;
}

}  // namespace

Paths united_by_strips(const std::vector<Paths>& pieces,
                       const std::function<Paths(const Paths&)>& united) {
  std::vector<Paths> strips = united_strips(pieces, united);
  if (strips.size() == 1) return std::move(strips[0]);
  return joined_strips(std::move(strips));
}

Paths grown_islands(const std::vector<Island>& islands, double delta_nm, double arc_tolerance_nm) {
  std::vector<Paths> pieces;  // a board of fewer vertices than a strip is one offset
  pieces.reserve(islands.size());
  for (const Island& island : islands) pieces.push_back(island.paths);
  return united_by_strips(pieces, [&](const Paths& group) {
    return offset_together(group, delta_nm, arc_tolerance_nm, ClipperLib::etClosedPolygon);
  });
}

Paths offset_closed(const Paths& paths, double delta_nm, double arc_tolerance_nm) {
  // A shrink does not distribute over a union (touching pieces): done in one piece.
  if (delta_nm <= 0 || vertex_count(paths) <= kStripVertices)
    return offset_together(paths, delta_nm, arc_tolerance_nm, ClipperLib::etClosedPolygon);
  return grown_islands(copper_islands(paths), delta_nm, arc_tolerance_nm);
}

namespace {

std::vector<Paths> one_piece_each(const Paths& paths) {
  std::vector<Paths> pieces;
  pieces.reserve(paths.size());
  for (const Path& p : paths) pieces.push_back(Paths{p});
  return pieces;
}

}  // namespace

Paths sweep_open(const Paths& paths, double radius_nm, double arc_tolerance_nm) {
  return united_by_strips(one_piece_each(paths), [&](const Paths& group) {
    return offset_together(group, radius_nm, arc_tolerance_nm, ClipperLib::etOpenRound);
  });
}

Paths sweep_open_unjoined(const Paths& paths, double radius_nm, double arc_tolerance_nm) {
  // The outlines all wind the same way (negative on the swept region), so the non-zero rule
  // unites them.
  Paths out;
  out.reserve(paths.size());
  for (const Path& p : paths) out.push_back(disc_sweep_outline(p, radius_nm, arc_tolerance_nm));
  return out;
}

namespace {

// a (op) b, both non-zero filled.
Paths clip(const Paths& a, const Paths& b, ClipperLib::ClipType op) {
  Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPaths(b, ClipperLib::ptClip, true);
  Paths out;
  c.Execute(op, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

}  // namespace

Paths intersection_of(const Paths& a, const Paths& b) {
  return clip(a, b, ClipperLib::ctIntersection);
}

Paths difference_of(const Paths& a, const Paths& b) {
  return clip(a, b, ClipperLib::ctDifference);
}

}  // namespace host::pcb
