// Grid search for the nearest unused curve end (see nearest_end.h).
#include "host/lib/plan/nearest_end.h"

#include <algorithm>  // std::max, std::find
#include <cmath>      // std::sqrt, std::floor
#include <cstdlib>    // std::labs
#include <stdexcept>  // std::length_error

namespace host {

NearestEnd::NearestEnd(const std::vector<Point2>& starts, const std::vector<Point2>& ends)
    : starts_(starts), ends_(ends), used_(starts.size(), false), left_(starts.size()) {
  if (starts_.empty()) return;
  if (starts_.size() > UINT32_MAX / 2) throw std::length_error("too many curves to order");
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
  // Two passes (count, then fill) instead of a vector per cell: no reallocation, 4 bytes
  // an end.
  const size_t cells = static_cast<size_t>(nx_ * ny_);
  count_.assign(cells, 0);
  for (size_t i = 0; i < starts_.size(); ++i) {
    ++count_[cell_index(starts_[i])];
    ++count_[cell_index(ends_[i])];
  }
  first_.resize(cells);
  uint32_t next = 0;
  for (size_t c = 0; c < cells; ++c) {
    first_[c] = next;
    next += count_[c];
    count_[c] = 0;
  }
  entries_.resize(next);
  for (size_t i = 0; i < starts_.size(); ++i) {
    for (int rev = 0; rev < 2; ++rev) {
      const size_t c = cell_index(rev ? ends_[i] : starts_[i]);
      entries_[first_[c] + count_[c]++] = static_cast<uint32_t>(i * 2 + rev);
    }
  }
}

size_t NearestEnd::cell_index(const Point2& p) const {
  return static_cast<size_t>(cell_of(p.x(), min_.x(), nx_) * ny_ + cell_of(p.y(), min_.y(), ny_));
}

size_t NearestEnd::held_bytes() const {
  return used_.capacity() / 8 +
         (first_.capacity() + count_.capacity() + entries_.capacity()) * sizeof(uint32_t);
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
        const size_t c = static_cast<size_t>(ix * ny_ + iy);
        for (uint32_t k = first_[c]; k < first_[c] + count_[c]; ++k) {
          const uint32_t e = entries_[k];
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
    const size_t c = cell_index(rev ? ends_[index] : starts_[index]);
    uint32_t* const begin = &entries_[first_[c]];
    uint32_t* const end = begin + count_[c];
    uint32_t* const it = std::find(begin, end, static_cast<uint32_t>(index * 2 + rev));
    if (it == end) continue;
    // The order within a cell does not matter: nearest() ranks by distance, index, side.
    *it = *(end - 1);
    --count_[c];
  }
}

}  // namespace host
