// Grid search for the nearest unused curve end (see nearest_end.h).
#include "host/lib/plan/nearest_end.h"

#include <algorithm>  // std::max, std::find
#include <cmath>      // std::sqrt, std::floor
#include <cstdlib>    // std::labs

namespace host {

NearestEnd::NearestEnd(const std::vector<Point2>& starts, const std::vector<Point2>& ends)
    : starts_(starts), ends_(ends), used_(starts.size(), false), left_(starts.size()) {
  if (starts_.empty()) return;
  Extents e;
  for (size_t i = 0; i < starts_.size(); ++i) {
    e.add(starts_[i]);
    e.add(ends_[i]);
  }
  min_ = e.min;
  const double w = std::max(e.width(), 1e-6), h = std::max(e.height(), 1e-6);
  // About two ends per cell.
  cell_ = std::max(std::sqrt(w * h / static_cast<double>(starts_.size())), 1e-6);
  nx_ = std::min<long>(static_cast<long>(w / cell_) + 1, 4096);
  ny_ = std::min<long>(static_cast<long>(h / cell_) + 1, 4096);
  cell_ = std::max(w / static_cast<double>(nx_), h / static_cast<double>(ny_)) * (1 + 1e-9);
  cells_.resize(static_cast<size_t>(nx_ * ny_));
  for (size_t i = 0; i < starts_.size(); ++i) {
    for (int rev = 0; rev < 2; ++rev) {
      const Point2& p = rev ? ends_[i] : starts_[i];
      const long cx = cell_of(p.x(), min_.x(), nx_), cy = cell_of(p.y(), min_.y(), ny_);
      cells_[static_cast<size_t>(cx * ny_ + cy)].push_back(i * 2 + rev);
    }
  }
}

long NearestEnd::cell_of(double v, double lo, long n) const {
  const long c = static_cast<long>(std::floor((v - lo) / cell_));
  return std::max(0L, std::min(n - 1, c));
}

NearestEnd::Hit NearestEnd::nearest(const Point2& p) const {
  Hit best;
  if (left_ == 0) return best;
  auto better = [](double d, size_t i, bool rev, const Hit& b) {
    if (d != b.distance) return d < b.distance;
    if (i != b.index) return i < b.index;
    return !rev && b.reversed;
  };
  const long cx = static_cast<long>(std::floor((p.x() - min_.x()) / cell_));
  const long cy = static_cast<long>(std::floor((p.y() - min_.y()) / cell_));
  const long max_ring = std::max(nx_, ny_) + std::labs(cx) + std::labs(cy) + 1;
  for (long ring = 0; ring <= max_ring; ++ring) {
    // Every end within ring-1 cells has been seen; a tie further out would need an equal
    // distance, which is beyond that bound.
    if (ring > 0 && best.distance < (ring - 1) * cell_) break;
    for (long ix = std::max(0L, cx - ring); ix <= std::min(nx_ - 1, cx + ring); ++ix) {
      const bool edge_x = std::labs(ix - cx) == ring;
      for (long iy = std::max(0L, cy - ring); iy <= std::min(ny_ - 1, cy + ring); ++iy) {
        if (!edge_x && std::labs(iy - cy) != ring) {
          iy = cy + ring - 1;  // inside the ring: on to its far edge
          continue;
        }
        for (size_t e : cells_[static_cast<size_t>(ix * ny_ + iy)]) {
          const size_t i = e / 2;
          const bool rev = (e & 1) != 0;
          const double d = ((rev ? ends_[i] : starts_[i]) - p).norm();
          if (better(d, i, rev, best)) best = Hit{i, rev, d};
        }
      }
    }
  }
  return best;
}

void NearestEnd::use(size_t index) {
  if (index >= used_.size() || used_[index]) return;
  used_[index] = true;
  --left_;
  for (int rev = 0; rev < 2; ++rev) {
    const Point2& p = rev ? ends_[index] : starts_[index];
    auto& cell = cells_[static_cast<size_t>(cell_of(p.x(), min_.x(), nx_) * ny_ +
                                            cell_of(p.y(), min_.y(), ny_))];
    const auto it = std::find(cell.begin(), cell.end(), index * 2 + rev);
    if (it != cell.end()) cell.erase(it);
  }
}

}  // namespace host
