// Host-only double-precision reference for the fixed-point spline core (Eigen Splines).
#ifndef HOST_TESTS_CORE_SPLINE_REFERENCE_H
#define HOST_TESTS_CORE_SPLINE_REFERENCE_H

#include <Eigen/Core>  // Eigen::Vector2d

#include "firmware/core/spline.h"  // core::Spline

namespace reference {

// The curve at knot-space parameter u (rational: homogeneous Eigen spline, then divide).
Eigen::Vector2d point_at(const core::Spline& s, double u);

// The curve at parameter t_q16 / 65536 of span `span` (knot[span] .. knot[span + 1]).
Eigen::Vector2d span_point(const core::Spline& s, int span, double t);

// Knot-space parameter of t in span.
double span_u(const core::Spline& s, int span, double t);

}  // namespace reference

#endif  // HOST_TESTS_CORE_SPLINE_REFERENCE_H
