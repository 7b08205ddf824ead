// Exact B-spline forms of the drawing primitives: lines (degree 1), circular arcs and
// ellipse arcs (rational quadratics, at most 90 degrees per piece), bulge polylines.
#ifndef HOST_LIB_DRAWING_CONICS_H
#define HOST_LIB_DRAWING_CONICS_H

#include <vector>  // std::vector

#include "host/lib/drawing/bspline.h"

namespace host {

// Straight segment a -> b, degree 1, knots [0 0 1 1].
BSpline line_spline(const Point2& a, const Point2& b);

// Arc of the circle (centre, radius) from start_rad sweeping sweep_rad (> 0 CCW, < 0 CW),
// |sweep| <= 2 pi, as a rational quadratic: ceil(|sweep| / 90 deg) pieces, middle weights
// cos(half piece angle), knots [0 0 0 1 1 2 2 ... n n n].
BSpline arc_spline(const Point2& centre, double radius, double start_rad, double sweep_rad);

// Ellipse arc centre + cos(t) major + sin(t) minor, t from t0 sweeping sweep (> 0): the
// affine image of the unit-circle arc (exact).
BSpline ellipse_spline(const Point2& centre, const Point2& major, const Point2& minor, double t0,
                       double sweep);

// A polyline vertex with the bulge of the segment that leaves it (tan(sweep / 4), > 0 CCW).
struct BulgeVertex {
  Point2 p;
  double bulge = 0.0;
};

// The polyline as one curve: degree 1 when it has no bulges, else rational quadratic with
// straight segments raised to degree 2. Zero-length segments are dropped. closed adds the
// segment from the last vertex back to the first. Returns an empty spline (no control
// points) when nothing is left to draw.
BSpline polyline_spline(const std::vector<BulgeVertex>& vertices, bool closed);

}  // namespace host

#endif  // HOST_LIB_DRAWING_CONICS_H
