// Grid-indexed nearest-segment distance for contour error measurement.
#include "host/lib/sim/contour_error.h"

#include <algorithm>  // std::min, std::max
#include <cmath>      // std::floor
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

}  // namespace

NearestSegment::NearestSegment(const std::vector<std::vector<Point2>>& polylines, double cell_mm)
    : cell_(cell_mm) {
  Point2 lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& line : polylines) {
    for (size_t i = 0; i + 1 < line.size(); ++i) segments_.push_back({line[i], line[i + 1]});
    if (line.size() == 1) segments_.push_back({line[0], line[0]});
    for (const Point2& p : line) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  if (segments_.empty()) return;
  min_ = lo;
  nx_ = static_cast<long>((hi.x() - lo.x()) / cell_) + 1;
  ny_ = static_cast<long>((hi.y() - lo.y()) / cell_) + 1;
  cells_.resize(static_cast<size_t>(nx_ * ny_));
  for (size_t s = 0; s < segments_.size(); ++s) {
    const Segment& g = segments_[s];
    const long x0 = static_cast<long>((std::min(g.a.x(), g.b.x()) - min_.x()) / cell_);
    const long x1 = static_cast<long>((std::max(g.a.x(), g.b.x()) - min_.x()) / cell_);
    const long y0 = static_cast<long>((std::min(g.a.y(), g.b.y()) - min_.y()) / cell_);
    const long y1 = static_cast<long>((std::max(g.a.y(), g.b.y()) - min_.y()) / cell_);
    for (long ix = x0; ix <= x1; ++ix) {
      for (long iy = y0; iy <= y1; ++iy)
        cells_[static_cast<size_t>(ix * ny_ + iy)].push_back(int(s));
    }
  }
}

double NearestSegment::distance(const Point2& p) const {
  if (segments_.empty()) return std::numeric_limits<double>::infinity();
  const double px = p.x(), py = p.y();
  auto dist2 = [&](int s) {
    const Segment& g = segments_[static_cast<size_t>(s)];
    return point_segment_distance2(px, py, g.a.x(), g.a.y(), g.b.x(), g.b.y());
  };
  // Consecutive queries follow the tool: the previous answer bounds the search at once.
  double best2 = dist2(hint_);
  int best_s = hint_;
  const long cx = static_cast<long>(std::floor((px - min_.x()) / cell_));
  const long cy = static_cast<long>(std::floor((py - min_.y()) / cell_));
  const long max_ring = std::max(nx_, ny_) + std::labs(cx) + std::labs(cy) + 1;
  // From p to the nearest side of its own cell: what ring 1 is at least away.
  const double fx = px - min_.x() - cx * cell_, fy = py - min_.y() - cy * cell_;
  const double edge = std::max(0.0, std::min(std::min(fx, cell_ - fx), std::min(fy, cell_ - fy)));
  for (long ring = 0; ring <= max_ring; ++ring) {
    // Every segment nearer than the ring's inner bound has been seen: stop when one beats it.
    const double bound = (ring - 1) * cell_ + edge;
    if (ring > 0 && best2 <= bound * bound) break;
    for (long ix = std::max(0L, cx - ring); ix <= std::min(nx_ - 1, cx + ring); ++ix) {
      const bool edge_x = std::labs(ix - cx) == ring;
      for (long iy = std::max(0L, cy - ring); iy <= std::min(ny_ - 1, cy + ring); ++iy) {
        if (!edge_x && std::labs(iy - cy) != ring) {
          iy = cy + ring - 1;  // inside the ring: jump to its far edge
          continue;
        }
        for (int s : cells_[static_cast<size_t>(ix * ny_ + iy)]) {
          const double d2 = dist2(s);
          if (d2 < best2) {
            best2 = d2;
            best_s = s;
          }
        }
      }
    }
  }
  hint_ = best_s;
  return std::sqrt(best2);
}

}  // namespace host::sim
