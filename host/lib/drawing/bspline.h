// Host geometry: a B-spline in millimetres (doubles, Eigen), the form every drawing entity
// is converted to, with the operations the importer, planner and plotter share.
#ifndef HOST_LIB_DRAWING_BSPLINE_H
#define HOST_LIB_DRAWING_BSPLINE_H

#include <Eigen/Core>  // Eigen::Vector2d
#include <string>      // std::string
#include <vector>      // std::vector

namespace host {

typedef Eigen::Vector2d Point2;

// A (possibly rational) B-spline curve. knots.size() == control.size() + degree + 1;
// weights is empty for a polynomial spline, else one positive weight per control point.
// The curve is defined on [knots[degree], knots[control.size()]].
struct BSpline {
  int degree = 0;
  std::vector<Point2> control;
  std::vector<double> weights;
  std::vector<double> knots;

  bool rational() const { return !weights.empty(); }
  double weight(size_t i) const { return weights.empty() ? 1.0 : weights[i]; }
  double t_min() const { return knots[degree]; }
  double t_max() const { return knots[control.size()]; }
};

// Empty string when the spline is well formed (degree 1..3 or more, counts match, knots
// non-decreasing, a non-empty range, finite values, positive weights), else what is wrong.
std::string check_bspline(const BSpline& s);

// Point on the curve at parameter t (clamped to the valid range). De Boor in homogeneous
// coordinates.
Point2 evaluate(const BSpline& s, double t);

// The curve traversed the other way: control points (and weights) reversed, knots
// negated and reversed (so the parameter range becomes [-t_max, -t_min]).
BSpline reversed(const BSpline& s);

// Inserts knot u once (Boehm), leaving the shape unchanged.
BSpline insert_knot(const BSpline& s, double u);

// Same curve with end knots of full multiplicity (degree + 1) on the valid range: the
// first and last control points are then the curve's end points.
BSpline clamped(const BSpline& s);

// The curve cut into its Bezier pieces (one per non-empty knot span), each clamped with
// knots [a..a, b..b] of the span it came from.
std::vector<BSpline> bezier_pieces(const BSpline& s);

// Start and end points of the curve.
Point2 start_point(const BSpline& s);
Point2 end_point(const BSpline& s);

// Applies x' = A x + b to the curve (B-splines are affine invariant, rational ones too).
BSpline transformed(const BSpline& s, const Eigen::Matrix2d& a, const Point2& b);

// Points along the curve whose chords stay within tol_mm of it (recursive subdivision
// per knot span, measured at the chord midpoints' parameters), including both ends.
std::vector<Point2> sample(const BSpline& s, double tol_mm);

// Axis-aligned bounds of a set of points.
struct Extents {
  Point2 min{1e300, 1e300};
  Point2 max{-1e300, -1e300};
  bool empty() const { return min.x() > max.x(); }
  void add(const Point2& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const Extents& e) {
    if (!e.empty()) {
      add(e.min);
      add(e.max);
    }
  }
  double width() const { return empty() ? 0 : max.x() - min.x(); }
  double height() const { return empty() ? 0 : max.y() - min.y(); }
};

// Tight extents of the curve, within 1 nm (1e-12 of its size beyond 1 km): the Bezier
// pieces that reach beyond the extents found so far are halved until they do not.
Extents curve_extents(const BSpline& s);

}  // namespace host

#endif  // HOST_LIB_DRAWING_BSPLINE_H
