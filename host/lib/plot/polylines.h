// Polylines in one flat list, in float mm (a plot's pixel is far coarser than a float's step
// at a machine's size): a million two-point lines take 20 bytes each, not the ~72 of a
// vector apiece, so the plot of a large job fits beside its plan.
#ifndef HOST_LIB_PLOT_POLYLINES_H
#define HOST_LIB_PLOT_POLYLINES_H

#include <array>       // std::array
#include <cstddef>     // size_t
#include <cstdint>     // uint32_t
#include <functional>  // std::function
#include <vector>      // std::vector

#include "host/lib/drawing/bspline.h"  // Point2

namespace host {

class Polylines {
 public:
  void push_back(const std::vector<Point2>& points_mm);
  size_t size() const { return starts_.size(); }
  bool empty() const { return starts_.empty(); }
  void reserve(size_t polylines) { starts_.reserve(polylines); }
  // Each polyline in order (handed out in one buffer, reused).
  void each(const std::function<void(const std::vector<Point2>&)>& fn) const;
  size_t heap_bytes() const;

 private:
  std::vector<std::array<float, 2>> points_;
  std::vector<uint32_t> starts_;  // polyline k is points_[starts_[k] .. starts_[k + 1])
};

}  // namespace host

#endif  // HOST_LIB_PLOT_POLYLINES_H
