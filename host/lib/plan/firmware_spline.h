// Converts a host B-spline (mm, doubles) to the firmware's fixed-point core::Spline form:
// int32 micrometre control points, Q14 weights, int32 knots; splits long curves.
#ifndef HOST_LIB_PLAN_FIRMWARE_SPLINE_H
#define HOST_LIB_PLAN_FIRMWARE_SPLINE_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "firmware/core/spline.h"
#include "host/lib/drawing/bspline.h"

namespace host {

// A curve the firmware form cannot hold (coordinates beyond core::kMaxCoordinateUm,
// weights spanning more than the Q14 range can keep, ...). what() says which and why.
class ConversionError : public std::runtime_error {
 public:
  explicit ConversionError(const std::string& msg) : std::runtime_error(msg) {}
};

// The curve as one or more firmware splines traced one after the other, same shape:
// - control points rounded to the nearest micrometre;
// - weights multiplied by a common factor (which does not change a rational curve) so the
//   largest lands in [2, 4) of Q2.14 at the factor that minimises the worst relative
//   rounding error, then rounded; a polynomial spline keeps rational = false;
// - knots mapped affinely (k - k_first) * scale, rounded, with the scale chosen so the
//   whole knot vector spans kKnotRangeTarget integer units (spans stay proportional);
// - a curve with more than core::kMaxControlPoints control points is cut at interior knots
//   (by knot insertion up to full multiplicity), each piece within the limit.
// Every returned spline passes core::validate_spline. Throws ConversionError otherwise.
std::vector<core::Spline> to_firmware_splines(const BSpline& mm_spline);

// Integer units the knot vector of each converted spline spans: relative knot precision
// 4e-9, far from int32 overflow (the firmware takes any int32 knots, core/spline.cpp).
static const long kKnotRangeTarget = 1L << 28;

// The firmware spline back in host form (mm, doubles): for tests and plots.
BSpline from_firmware_spline(const core::Spline& s);

}  // namespace host

#endif  // HOST_LIB_PLAN_FIRMWARE_SPLINE_H
