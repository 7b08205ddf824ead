// Grid-indexed nearest-segment distance for contour error measurement.
#include "host/lib/sim/contour_error.h"

#include <algorithm>  // std::min, std::max
#include <cmath>      // std::floor
#include <cstdlib>    // std::labs
#include <limits>     // std::numeric_limits

namespace host::sim {

namespace {

double point_segment_distance(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
  t = std::max(0.0, std::min(1.0, t));
  return (a + t * ab - p).norm();
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
  double best = std::numeric_limits<double>::infinity();
  if (segments_.empty()) return best;
  const long cx = static_cast<long>(std::floor((p.x() - min_.x()) / cell_));
  const long cy = static_cast<long>(std::floor((p.y() - min_.y()) / cell_));
  const long max_ring = std::max(nx_, ny_) + std::labs(cx) + std::labs(cy) + 1;
  for (long ring = 0; ring <= max_ring; ++ring) {
    // Every segment within ring-1 cells has been seen: stop when that bound beats them.
    if (ring > 0 && best <= (ring - 1) * cell_) break;
    for (long ix = std::max(0L, cx - ring); ix <= std::min(nx_ - 1, cx + ring); ++ix) {
      for (long iy = std::max(0L, cy - ring); iy <= std::min(ny_ - 1, cy + ring); ++iy) {
        if (std::max(std::labs(ix - cx), std::labs(iy - cy)) != ring) continue;
        for (int s : cells_[static_cast<size_t>(ix * ny_ + iy)]) {
          best = std::min(best, point_segment_distance(p, segments_[s].a, segments_[s].b));
        }
      }
    }
  }
  return best;
}

}  // namespace host::sim
