// Grid-indexed nearest-segment distance for contour error measurement.
#include "host/lib/sim/contour_error.h"

#include <algorithm>  // std::min, std::max, std::nth_element, std::sort
#include <cmath>      // std::floor, std::sqrt
#include <cstdlib>    // std::labs
#include <limits>     // std::numeric_limits

namespace host::sim {

namespace {

// Plain doubles: this runs for every pen-down sample of a job (millions), also in Debug.
double point_segment_distance2(double px, double py, double ax, double ay, double bx, double by) {
  const double abx = bx - ax, aby = by - ay;
  const double len2 = abx * abx + aby * aby;
  double t = len2 > 0 ? ((px - ax) * abx + (py - ay) * aby) / len2 : 0.0;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  const double dx = ax + t * abx - px, dy = ay + t * aby - py;
  return dx * dx + dy * dy;
}

// The fine grid's cell is this many times the median segment's extent (a cell then holds a
// few segments), and it is used only when that is below the coarse cell / kFineUse.
constexpr double kFinePerSegment = 4.0;
constexpr double kFineUse = 8.0;
constexpr double kFineMinMm = 0.0005;
// Rings of fine cells searched before the coarse grid is asked (a contour error within
// about three fine cells, as on any job that follows its path, never needs it).
constexpr long kFineRings = 3;
// Segments after the previous nearest one that upper_bound() tries (a millisecond of tool
// travel crosses one or two of a fine contour's).
constexpr size_t kLookAhead = 2;

uint64_t fine_key(long ix, long iy) {
  return (static_cast<uint64_t>(ix) << 32) | static_cast<uint32_t>(iy);
}

double extent_of(const Point2& a, const Point2& b) {
  return std::max(std::abs(b.x() - a.x()), std::abs(b.y() - a.y()));
}

// Calls f(ix, iy) for every cell of a grid (origin, cell) that segment s passes through,
// column by column: a diagonal line n cells long is in ~2n cells, not the n x n of its
// bounding box (a million random lines' index: ~18 cells a line before, ~8 now). The search
// stays exact: every point of a segment lies in a cell that lists it. A column's rows are
// widened by kEdgeCells so that rounding never drops a cell the segment only touches.
constexpr double kEdgeCells = 1e-9;
template <typename F>
void for_cells_crossed(const Point2& a, const Point2& b, const Point2& origin, double cell, F&& f) {
  const double ax = (a.x() - origin.x()) / cell, ay = (a.y() - origin.y()) / cell;
  const double bx = (b.x() - origin.x()) / cell, by = (b.y() - origin.y()) / cell;
  const long x0 = static_cast<long>(std::min(ax, bx)), x1 = static_cast<long>(std::max(ax, bx));
  const long y0 = static_cast<long>(std::min(ay, by)), y1 = static_cast<long>(std::max(ay, by));
  const double dx = bx - ax;
  for (long ix = x0; ix <= x1; ++ix) {
    long r0 = y0, r1 = y1;
    if (x0 < x1 && dx != 0) {
      // The segment's y where it enters and leaves this column.
      const double xa = std::max(static_cast<double>(ix), std::min(ax, bx));
      const double xb = std::min(static_cast<double>(ix + 1), std::max(ax, bx));
      const double ya = ay + (by - ay) * ((xa - ax) / dx), yb = ay + (by - ay) * ((xb - ax) / dx);
      r0 = std::max(y0, static_cast<long>(std::floor(std::min(ya, yb) - kEdgeCells)));
      r1 = std::min(y1, static_cast<long>(std::floor(std::max(ya, yb) + kEdgeCells)));
    }
    for (long iy = r0; iy <= r1; ++iy) f(ix, iy);
  }
}

}  // namespace

NearestSegment::NearestSegment(const std::vector<std::vector<Point2>>& polylines, double cell_mm)
    : cell_(cell_mm) {
  for (const auto& line : polylines) add(line);
  index();
}

void NearestSegment::add(const std::vector<Point2>& line) {
  for (size_t i = 0; i + 1 < line.size(); ++i) segments_.push_back({line[i], line[i + 1]});
  if (line.size() == 1) segments_.push_back({line[0], line[0]});
}

void NearestSegment::index() {
  if (segments_.empty()) return;
  if (segments_.capacity() > segments_.size() + segments_.size() / 4) segments_.shrink_to_fit();
  Point2 lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Segment& s : segments_) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  min_ = lo;
  max_ = hi;
  {
    std::vector<float> extents;
    extents.reserve(segments_.size());
    for (const Segment& s : segments_) extents.push_back(static_cast<float>(extent_of(s.a, s.b)));
    std::nth_element(extents.begin(), extents.begin() + extents.size() / 2, extents.end());
    const double fine = std::max(kFinePerSegment * extents[extents.size() / 2], kFineMinMm);
    if (fine <= cell_ / kFineUse) fine_cell_ = fine;
  }
  coarse_.cell = cell_;
  build_coarse(&coarse_, false);
  if (fine_cell_ > 0) {
    build_fine();
    coarse_long_.cell = cell_;
    build_coarse(&coarse_long_, true);
  }
}

bool NearestSegment::is_short(const Segment& s) const {
  return fine_cell_ > 0 && extent_of(s.a, s.b) <= fine_cell_;
}

void NearestSegment::build_coarse(Grid* g, bool long_only) const {
  g->nx = static_cast<long>((max_.x() - min_.x()) / g->cell) + 1;
  g->ny = static_cast<long>((max_.y() - min_.y()) / g->cell) + 1;
  const size_t cells = static_cast<size_t>(g->nx * g->ny);
  // Two passes (count, then fill): one array of entries, no list per cell.
  g->start.assign(cells + 1, 0);
  auto for_cells = [&](const Segment& s, auto&& f) {
    for_cells_crossed(s.a, s.b, min_, g->cell,
                      [&](long ix, long iy) { f(static_cast<size_t>(ix * g->ny + iy)); });
  };
  for (const Segment& s : segments_) {
    if (long_only && is_short(s)) continue;
    for_cells(s, [&](size_t c) { ++g->start[c + 1]; });
  }
  for (size_t c = 0; c < cells; ++c) g->start[c + 1] += g->start[c];
  g->entries.resize(g->start[cells]);
  std::vector<uint32_t> fill(g->start.begin(), g->start.end() - 1);
  for (size_t i = 0; i < segments_.size(); ++i) {
    if (long_only && is_short(segments_[i])) continue;
    for_cells(segments_[i], [&](size_t c) { g->entries[fill[c]++] = static_cast<uint32_t>(i); });
  }
  if (g->entries.empty()) *g = Grid();
}

void NearestSegment::build_fine() {
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  for (size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    if (!is_short(s)) continue;
    const long x0 = static_cast<long>((std::min(s.a.x(), s.b.x()) - min_.x()) / fine_cell_);
    const long x1 = static_cast<long>((std::max(s.a.x(), s.b.x()) - min_.x()) / fine_cell_);
    const long y0 = static_cast<long>((std::min(s.a.y(), s.b.y()) - min_.y()) / fine_cell_);
    const long y1 = static_cast<long>((std::max(s.a.y(), s.b.y()) - min_.y()) / fine_cell_);
    for (long ix = x0; ix <= x1; ++ix)
      for (long iy = y0; iy <= y1; ++iy) keyed.emplace_back(fine_key(ix, iy), uint32_t(i));
  }
  std::sort(keyed.begin(), keyed.end());
  fine_entries_.reserve(keyed.size());
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) {
      fine_cells_[keyed[i].first] = {static_cast<uint32_t>(fine_entries_.size()),
                                     static_cast<uint32_t>(fine_entries_.size())};
    }
    fine_entries_.push_back(keyed[i].second);
    fine_cells_[keyed[i].first].second = static_cast<uint32_t>(fine_entries_.size());
  }
}

size_t NearestSegment::held_bytes() const {
  size_t n = segments_.capacity() * sizeof(Segment) + fine_entries_.capacity() * sizeof(uint32_t);
  for (const Grid* g : {&coarse_, &coarse_long_})
    n += (g->start.capacity() + g->entries.capacity()) * sizeof(uint32_t);
  // A node of the fine grid's map: the key, its range and the bucket's link, about.
  return n + fine_cells_.size() * 32 + fine_cells_.bucket_count() * sizeof(void*);
}

double NearestSegment::dist2(uint32_t s, double px, double py) const {
  ++examined_;
  const Segment& g = segments_[s];
  return point_segment_distance2(px, py, g.a.x(), g.a.y(), g.b.x(), g.b.y());
}

double NearestSegment::search(const Grid& g, const Point2& p, double* best2,
                              uint32_t* best_s) const {
  const double px = p.x(), py = p.y();
  const long cx = static_cast<long>(std::floor((px - min_.x()) / g.cell));
  const long cy = static_cast<long>(std::floor((py - min_.y()) / g.cell));
  const long max_ring = std::max(g.nx, g.ny) + std::labs(cx) + std::labs(cy) + 1;
  // From p to the nearest side of its own cell: what ring 1 is at least away.
  const double fx = px - min_.x() - cx * g.cell, fy = py - min_.y() - cy * g.cell;
  const double edge = std::max(0.0, std::min(std::min(fx, g.cell - fx), std::min(fy, g.cell - fy)));
  for (long ring = 0; ring <= max_ring; ++ring) {
    // Every segment nearer than the ring's inner bound has been seen: stop when one beats it.
    const double bound = (ring - 1) * g.cell + edge;
    if (ring > 0 && *best2 <= bound * bound) return bound;
    for (long ix = std::max(0L, cx - ring); ix <= std::min(g.nx - 1, cx + ring); ++ix) {
      const bool edge_x = std::labs(ix - cx) == ring;
      for (long iy = std::max(0L, cy - ring); iy <= std::min(g.ny - 1, cy + ring); ++iy) {
        if (!edge_x && std::labs(iy - cy) != ring) {
          iy = cy + ring - 1;  // inside the ring: jump to its far edge
          continue;
        }
        const size_t c = static_cast<size_t>(ix * g.ny + iy);
        for (uint32_t k = g.start[c]; k < g.start[c + 1]; ++k) {
          const double d2 = dist2(g.entries[k], px, py);
          if (d2 < *best2) {
            *best2 = d2;
            *best_s = g.entries[k];
          }
        }
      }
    }
  }
  return std::numeric_limits<double>::infinity();
}

double NearestSegment::search_fine(const Point2& p, double* best2, uint32_t* best_s) const {
  const double px = p.x(), py = p.y(), cell = fine_cell_;
  const long cx = static_cast<long>(std::floor((px - min_.x()) / cell));
  const long cy = static_cast<long>(std::floor((py - min_.y()) / cell));
  const double fx = px - min_.x() - cx * cell, fy = py - min_.y() - cy * cell;
  const double edge = std::max(0.0, std::min(std::min(fx, cell - fx), std::min(fy, cell - fy)));
  for (long ring = 0; ring <= kFineRings; ++ring) {
    const double bound = (ring - 1) * cell + edge;
    if (ring > 0 && *best2 <= bound * bound) return bound;
    for (long ix = cx - ring; ix <= cx + ring; ++ix) {
      const bool edge_x = std::labs(ix - cx) == ring;
      for (long iy = cy - ring; iy <= cy + ring; ++iy) {
        if (!edge_x && std::labs(iy - cy) != ring) {
          iy = cy + ring - 1;
          continue;
        }
        if (ix < 0 || iy < 0) continue;  // below the extents: no segment there
        const auto it = fine_cells_.find(fine_key(ix, iy));
        if (it == fine_cells_.end()) continue;
        for (uint32_t k = it->second.first; k < it->second.second; ++k) {
          const double d2 = dist2(fine_entries_[k], px, py);
          if (d2 < *best2) {
            *best2 = d2;
            *best_s = fine_entries_[k];
          }
        }
      }
    }
  }
  return kFineRings * cell + edge;
}

double NearestSegment::upper_bound(const Point2& p, double enough_mm) const {
  if (segments_.empty()) return std::numeric_limits<double>::infinity();
  double best2 = dist2(hint_, p.x(), p.y());
  if (best2 <= enough_mm * enough_mm) return std::sqrt(best2);
  const size_t first = hint_ + 1;
  const size_t last = std::min(segments_.size(), first + kLookAhead);
  for (size_t s = first; s < last; ++s) {
    const double d2 = dist2(static_cast<uint32_t>(s), p.x(), p.y());
    if (d2 < best2) {
      best2 = d2;
      hint_ = static_cast<uint32_t>(s);
    }
  }
  return std::sqrt(best2);
}

double NearestSegment::distance(const Point2& p) const {
  if (segments_.empty()) return std::numeric_limits<double>::infinity();
  // Consecutive queries follow the tool: the previous answer bounds the search at once.
  double best2 = dist2(hint_, p.x(), p.y());
  uint32_t best_s = hint_;
  bool done = false;
  if (fine_cell_ > 0) {
    // Every short segment within `covered` has been seen; the long ones are searched out.
    const double covered = search_fine(p, &best2, &best_s);
    if (!coarse_long_.entries.empty()) search(coarse_long_, p, &best2, &best_s);
    done = best2 <= covered * covered;
  }
  if (!done) search(coarse_, p, &best2, &best_s);
  hint_ = best_s;
  return std::sqrt(best2);
}

}  // namespace host::sim
