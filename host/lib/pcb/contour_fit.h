// Tool-centre polylines (Clipper's flattened output) back into the firmware's curve kinds:
// straight runs as lines, runs of vertices on a common circle as exact rational quadratic
// arcs, the remaining runs of short segments as cubic B-splines fitted within the chord
// tolerance.
#ifndef HOST_LIB_PCB_CONTOUR_FIT_H
#define HOST_LIB_PCB_CONTOUR_FIT_H

#include <vector>  // std::vector

#include "host/lib/drawing/bspline.h"  // BSpline, Point2

namespace host::pcb {

struct FitStats {
  int lines = 0;   // straight segments kept
  int arcs = 0;    // circular arcs recovered (each up to a full circle)
  int cubics = 0;  // runs fitted with a cubic B-spline
  int input_vertices = 0;
};

struct FitOptions {
  double tolerance_mm = 0.002;    // largest distance of the curves from the polyline's
                                  // vertices (arcs: chord sagittas up to 3x this are accepted)
  int min_arc_segments = 3;       // fewer consecutive segments on a circle stay lines
  int min_cubic_segments = 6;     // shorter runs of short segments stay lines
  double short_segment_mm = 0.2;  // segments shorter than this may be fitted as a cubic
};

// Curves that trace the polyline from its first to its last vertex, one after the other.
// A closed contour is given without repeating the first vertex and traced back to it.
// Lines and arcs share one rational quadratic B-spline (a polyline with no arc: degree 1);
// a cubic run is a spline of its own.
std::vector<BSpline> fit_polyline(const std::vector<Point2>& pts, bool closed,
                                  const FitOptions& options, FitStats* stats);

// The largest distance from the polyline's vertices to the curves (dense sampling), for
// tests. Between vertices an arc lies off the chord by the chord's sagitta (the polyline
// is the flattened arc, not the other way round).
double max_deviation_mm(const std::vector<Point2>& pts, bool closed,
                        const std::vector<BSpline>& curves);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_CONTOUR_FIT_H
