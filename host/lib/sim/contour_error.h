// How far a simulated tool path strays from the curves it should follow.
#ifndef HOST_LIB_SIM_CONTOUR_ERROR_H
#define HOST_LIB_SIM_CONTOUR_ERROR_H

#include <vector>  // std::vector

#include "host/lib/drawing/bspline.h"  // host::Point2

namespace host::sim {

// Distance from each point to the nearest segment of any polyline, indexed on a grid so a
// whole job (1e5 points, 1e5 segments) takes milliseconds.
class NearestSegment {
 public:
  NearestSegment(const std::vector<std::vector<Point2>>& polylines, double cell_mm = 0.5);
  // Distance in mm; searches outward ring by ring until no closer segment can exist.
  double distance(const Point2& p) const;

 private:
  struct Segment {
    Point2 a, b;
  };
  double cell_;
  Point2 min_;
  long nx_ = 0, ny_ = 0;
  std::vector<Segment> segments_;
  std::vector<std::vector<int>> cells_;  // nx_ * ny_ lists of segment indices
  mutable int hint_ = 0;                 // the previous query's nearest segment
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_CONTOUR_ERROR_H
