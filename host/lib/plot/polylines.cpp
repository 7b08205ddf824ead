// Polylines in one flat list (see polylines.h).
#include "host/lib/plot/polylines.h"

#include <stdexcept>  // std::length_error

namespace host {

void Polylines::push_back(const std::vector<Point2>& points_mm) {
  if (points_.size() + points_mm.size() > UINT32_MAX)
    throw std::length_error("plot: more than 4 294 967 295 points");
  starts_.push_back(static_cast<uint32_t>(points_.size()));
  for (const Point2& p : points_mm)
    points_.push_back({static_cast<float>(p.x()), static_cast<float>(p.y())});
}

void Polylines::each(const std::function<void(const std::vector<Point2>&)>& fn) const {
  std::vector<Point2> line;
  for (size_t k = 0; k < starts_.size(); ++k) {
    const size_t end = k + 1 < starts_.size() ? starts_[k + 1] : points_.size();
    line.clear();
    for (size_t i = starts_[k]; i < end; ++i) line.emplace_back(points_[i][0], points_[i][1]);
    fn(line);
  }
}

size_t Polylines::heap_bytes() const {
  return points_.capacity() * sizeof(points_[0]) + starts_.capacity() * sizeof(starts_[0]);
}

}  // namespace host
