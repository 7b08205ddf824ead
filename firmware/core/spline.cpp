// Validation of a stored B-spline: every condition the evaluator and walker rely on.
#include "firmware/core/spline.h"

namespace core {

// True when |v| is within the accepted coordinate range.
static bool coordinate_ok(int32_t v) {
  return v >= -kMaxCoordinateUm && v <= kMaxCoordinateUm;
}

// Checks, in order: degree, counts, knot order, non-empty domain, coordinates, weights.
// The order is part of the contract (one code per spline, the first problem found).
GeometryError validate_spline(const Spline& spline) {
  const uint16_t p = spline.degree;
  if (p == 0 || p > kMaxDegree) return GeometryError::kDegreeUnsupported;
  if (spline.control_count > kMaxControlPoints) return GeometryError::kTooManyControlPoints;
  if (spline.control_count < p + 1) return GeometryError::kTooFewControlPoints;
  if (spline.knot_count != spline.control_count + p + 1) return GeometryError::kKnotCountMismatch;
  for (uint16_t i = 0; i + 1 < spline.knot_count; ++i) {
    if (spline.knot[i + 1] < spline.knot[i]) return GeometryError::kKnotsDecreasing;
  }
  // The curve lives on [knot[p], knot[n]]; it needs one span of positive length there.
  if (spline.knot[spline.control_count] == spline.knot[p]) return GeometryError::kKnotRangeEmpty;
  for (uint16_t i = 0; i < spline.control_count; ++i) {
    const ControlPoint& c = spline.control[i];
    if (!coordinate_ok(c.x_um) || !coordinate_ok(c.y_um)) {
      return GeometryError::kCoordinateOutOfRange;
    }
    if (spline.rational && c.weight_q14 == 0) return GeometryError::kZeroWeight;
  }
  // kKnotSpanTooLong is never returned: knot differences are taken as 32-bit unsigned
  // values and normalised per span in 64-bit arithmetic, so any int32 range works.
  return GeometryError::kOk;
}

}  // namespace core
