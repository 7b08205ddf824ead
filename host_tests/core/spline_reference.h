// Host-only double-precision reference for the fixed-point spline core (Eigen Splines).
#ifndef HOST_TESTS_CORE_SPLINE_REFERENCE_H
#define HOST_TESTS_CORE_SPLINE_REFERENCE_H

#include <Eigen/Core>                 // Eigen::Vector2d
#include <unsupported/Eigen/Splines>  // Eigen::Spline

#include "firmware/core/spline.h"  // core::Spline

namespace reference {

// A spline converted once to an Eigen homogeneous spline (for loops).
class Curve {
 public:
  explicit Curve(const core::Spline& s);
  Eigen::Vector2d at(double u) const;
  Eigen::Vector2d at_span(int span, double t) const;
  // dP/du at u (quotient rule for rational curves).
  Eigen::Vector2d derivative(double u) const;
  // Signed curvature at u (> 0 turning left); polynomial curves only.
  double curvature(double u) const;

 private:
  core::Spline spline_;
  Eigen::Spline<double, 3> eigen_;
};

// The curve at knot-space parameter u (rational: homogeneous Eigen spline, then divide).
Eigen::Vector2d point_at(const core::Spline& s, double u);

// The curve at parameter t_q16 / 65536 of span `span` (knot[span] .. knot[span + 1]).
Eigen::Vector2d span_point(const core::Spline& s, int span, double t);

// Knot-space parameter of t in span.
double span_u(const core::Spline& s, int span, double t);

}  // namespace reference

#endif  // HOST_TESTS_CORE_SPLINE_REFERENCE_H
