// The greedy ordering's search: which unused curve end lies nearest to a point, on a grid,
// so ordering n curves costs about n log n instead of n^2 (100 000 curves: 0.3 s, not 75 s).
#ifndef HOST_LIB_PLAN_NEAREST_END_H
#define HOST_LIB_PLAN_NEAREST_END_H

#include <stdint.h>  // uint32_t

#include <cstddef>  // size_t
#include <vector>   // std::vector

#include "host/lib/drawing/bspline.h"  // Point2

namespace host {

class NearestEnd {
 public:
  // Reads the ends where they are: both vectors must outlive the index (a copy of them was
  // 32 MB of a million-line job).
  NearestEnd(const std::vector<Point2>& starts, const std::vector<Point2>& ends);
  NearestEnd(std::vector<Point2>&&, std::vector<Point2>&&) = delete;  // would dangle
  struct Hit {
    size_t index = 0;
    bool reversed = false;  // the nearest end is the curve's end: trace it backwards
    double distance = 1e300;
  };
  // The nearest end of an unused curve: the smallest distance, then the lowest index, then
  // the start before the end (what a scan over all curves in order finds). None left: a
  // hit with distance 1e300.
  Hit nearest(const Point2& p) const;
  void use(size_t index);
  // Bytes the index holds besides the ends it reads: about 16 per curve (a vector per cell
  // held ~90 for a million lines).
  size_t held_bytes() const;

 private:
  long cell_of(double v, double lo, long n) const;
  size_t cell_index(const Point2& p) const;
  const std::vector<Point2>& starts_;
  const std::vector<Point2>& ends_;
  std::vector<bool> used_;
  size_t left_ = 0;
  Point2 min_{0, 0};
  double cell_ = 1.0;
  long nx_ = 1, ny_ = 1;
  // The cells in compressed rows: cell c's unused ends are entries_[first_[c], first_[c] +
  // count_[c]), each index * 2 + (1 if the curve's end); a used one is swapped out.
  std::vector<uint32_t> first_;
  std::vector<uint32_t> count_;
  std::vector<uint32_t> entries_;
};

}  // namespace host

#endif  // HOST_LIB_PLAN_NEAREST_END_H
