// Drilling order: holes grouped by tool (diameter), each group ordered to shorten the travel
// (nearest neighbour, then 2-opt), with the travel in the file's order for comparison.
#ifndef HOST_LIB_PCB_DRILL_ORDER_H
#define HOST_LIB_PCB_DRILL_ORDER_H

#include <vector>  // std::vector

#include "host/lib/drawing/bspline.h"  // Point2
#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb {

struct DrillGroup {
  double diameter_mm = 0;
  int tool = 0;                    // the file's tool number (first seen for this size)
  std::vector<Point2> holes_mm;    // in drilling order
  std::vector<size_t> file_index;  // each hole's index in the input
};

struct DrillPlan {
  std::vector<DrillGroup> groups;   // smallest diameter first
  double travel_file_order_mm = 0;  // from the start point through the holes as listed
  double travel_ordered_mm = 0;     // the same holes, grouped and ordered
};

// Orders holes (positions in mm, already in the frame they will be drilled in) starting
// from `start`. Holes of equal diameter (to 1 um) share a group whatever their tool number.
DrillPlan order_holes(const std::vector<Point2>& at_mm, const std::vector<double>& diameter_mm,
                      const std::vector<int>& tool, const Point2& start);

// Length of the open path start -> pts[0] -> ... -> pts.back().
double travel_mm(const Point2& start, const std::vector<Point2>& pts);

// Nearest neighbour from start, then 2-opt until no exchange shortens the open path.
// Returns the visiting order (indices into pts).
std::vector<size_t> short_tour(const Point2& start, const std::vector<Point2>& pts);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_DRILL_ORDER_H
