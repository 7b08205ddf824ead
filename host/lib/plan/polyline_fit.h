// Fits runs of short straight segments (the way CAM programs write curves as G1 moves)
// with cubic B-splines that stay within a tolerance of the polyline, so a curve goes to
// the controller as a few control points instead of one feed per vertex.
#ifndef HOST_LIB_PLAN_POLYLINE_FIT_H
#define HOST_LIB_PLAN_POLYLINE_FIT_H

#include <vector>  // std::vector

#include "host/lib/drawing/bspline.h"

namespace host {

struct FitOptions {
  double tolerance_mm = 0.005;  // largest distance between the fit and the polyline
  double max_segment_mm = 2.0;  // longer segments are kept as they are (straight feeds)
  double corner_deg = 30.0;     // sharper turns are kept as corners
  int min_segments = 4;         // shorter runs are not worth a spline
  int max_control_points = 60;  // within the firmware's 64
};

// The polyline `points` as pieces traced one after another, each starting where the
// previous one ended: degree-1 polylines (kept segments) and clamped cubic B-splines (fitted
// runs). A fit is used only when it has fewer control points than the run has segments and
// every point of it is within tolerance_mm of the polyline and every vertex within
// tolerance_mm of it (both checked conservatively, by parameter).
std::vector<BSpline> fit_polyline(const std::vector<Point2>& points, const FitOptions& options);

}  // namespace host

#endif  // HOST_LIB_PLAN_POLYLINE_FIT_H
