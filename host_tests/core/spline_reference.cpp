// Eigen-based reference evaluation: B-spline in homogeneous coordinates, double precision.
#include "host_tests/core/spline_reference.h"

#include <cmath>  // std::hypot

namespace reference {

namespace {

// Homogeneous control points (w x, w y, w) and the knots, as Eigen wants them.
Eigen::Spline<double, 3> to_eigen(const core::Spline& s) {
  typedef Eigen::Spline<double, 3> Spline3;
  Spline3::KnotVectorType knots(s.knot_count);
  for (int i = 0; i < s.knot_count; ++i) knots(i) = s.knot[i];
  Spline3::ControlPointVectorType ctrl(3, s.control_count);
  for (int i = 0; i < s.control_count; ++i) {
    const double w = s.rational ? s.control[i].weight_q14 / 16384.0 : 1.0;
    ctrl(0, i) = w * s.control[i].x_um;
    ctrl(1, i) = w * s.control[i].y_um;
    ctrl(2, i) = w;
  }
  return Spline3(knots, ctrl);
}

}  // namespace

Curve::Curve(const core::Spline& s) : spline_(s), eigen_(to_eigen(s)) {}

Eigen::Vector2d Curve::at(double u) const {
  const Eigen::Spline<double, 3>::PointType h = eigen_(u);
  return Eigen::Vector2d(h(0) / h(2), h(1) / h(2));
}

Eigen::Vector2d Curve::derivative(double u) const {
  const Eigen::Matrix<double, 3, Eigen::Dynamic> d = eigen_.derivatives(u, 1);
  const double w = d(2, 0), dw = d(2, 1);
  return Eigen::Vector2d((d(0, 1) * w - d(0, 0) * dw) / (w * w),
                         (d(1, 1) * w - d(1, 0) * dw) / (w * w));
}

double Curve::curvature(double u) const {
  const Eigen::Matrix<double, 3, Eigen::Dynamic> d = eigen_.derivatives(u, 2);
  const double cross = d(0, 1) * d(1, 2) - d(1, 1) * d(0, 2);
  const double speed = std::hypot(d(0, 1), d(1, 1));
  return cross / (speed * speed * speed);
}

Eigen::Vector2d Curve::at_span(int span, double t) const {
  return at(span_u(spline_, span, t));
}

Eigen::Vector2d point_at(const core::Spline& s, double u) {
  return Curve(s).at(u);
}

double span_u(const core::Spline& s, int span, double t) {
  const double lo = s.knot[span];
  const double hi = s.knot[span + 1];
  return lo + t * (hi - lo);
}

Eigen::Vector2d span_point(const core::Spline& s, int span, double t) {
  return point_at(s, span_u(s, span, t));
}

}  // namespace reference
