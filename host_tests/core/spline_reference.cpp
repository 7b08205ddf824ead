// Eigen-based reference evaluation: B-spline in homogeneous coordinates, double precision.
#include "host_tests/core/spline_reference.h"

#include <unsupported/Eigen/Splines>  // Eigen::Spline

namespace reference {

Eigen::Vector2d point_at(const core::Spline& s, double u) {
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
  const Spline3 spline(knots, ctrl);
  const Spline3::PointType h = spline(u);
  return Eigen::Vector2d(h(0) / h(2), h(1) / h(2));
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
