// Independent reference evaluator for tests: Eigen's unsupported Splines module in double,
// rational curves through homogeneous coordinates (w x, w y, w).
#ifndef HOST_TESTS_HOST_DRAWING_EIGEN_REFERENCE_H
#define HOST_TESTS_HOST_DRAWING_EIGEN_REFERENCE_H

#include <unsupported/Eigen/Splines>  // Eigen::Spline

#include "host/lib/drawing/bspline.h"

namespace host::test {

// The point of s at parameter u (in [t_min, t_max]) by Eigen.
inline Point2 eigen_point(const BSpline& s, double u) {
  typedef Eigen::Spline<double, 3> Spline3;
  Spline3::KnotVectorType knots(s.knots.size());
  for (size_t i = 0; i < s.knots.size(); ++i) knots(i) = s.knots[i];
  Spline3::ControlPointVectorType ctrl(3, s.control.size());
  for (size_t i = 0; i < s.control.size(); ++i) {
    const double w = s.weight(i);
    ctrl.col(i) << s.control[i].x() * w, s.control[i].y() * w, w;
  }
  const Spline3 e(knots, ctrl);
  const Eigen::Vector3d h = e(u);
  return Point2(h.x() / h.z(), h.y() / h.z());
}

}  // namespace host::test

#endif  // HOST_TESTS_HOST_DRAWING_EIGEN_REFERENCE_H
