// A tool path as the plots draw it: positions with their pen state, 8 bytes and a bit each
// (float mm: a plot's pixel is far coarser than a float's step at a machine's size), so a
// simulated job of a million lines keeps its plot path in tens of MB, not hundreds.
#ifndef HOST_LIB_PLAN_PEN_PATH_H
#define HOST_LIB_PLAN_PEN_PATH_H

#include <array>       // std::array
#include <cstddef>     // size_t
#include <deque>       // std::deque
#include <functional>  // std::function
#include <vector>      // std::vector

#include "host/lib/drawing/bspline.h"  // Point2

namespace host {

// A piece of the path runs from the first position of its pen state to the first position
// of the next state (where the pen went up or down), so a piece needs no copy of its
// neighbour's end and thinning needs only the positions where the state changes.
class PenPath {
 public:
  void add(const Point2& p_mm, bool pen_down);
  size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }
  Point2 point(size_t i) const { return Point2(points_[i][0], points_[i][1]); }
  bool pen_down(size_t i) const { return down_[i]; }
  // Each piece with its state, in order: fn(points_mm, pen_down).
  void each_piece(const std::function<void(const std::vector<Point2>&, bool)>& fn) const;
  // Drops positions closer than step_mm (in X and in Y) to the last one kept; keeps both
  // ends and every position where the pen state changes.
  void thin(double step_mm);
  size_t heap_bytes() const;

 private:
  // In blocks, not one array: a vector doubling near the end of a long job held the old and
  // the new array at once (tens of MB at the peak of a million-line run).
  std::deque<std::array<float, 2>> points_;
  std::vector<bool> down_;
};

// The pen-down pieces (the cuts), each as a polyline.
std::vector<std::vector<Point2>> pen_down_pieces(const PenPath& path);

}  // namespace host

#endif  // HOST_LIB_PLAN_PEN_PATH_H
