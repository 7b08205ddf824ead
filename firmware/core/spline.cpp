// Validation of a stored B-spline: every condition the evaluator and walker rely on.
#include "firmware/core/spline.h"

namespace core {

GeometryError check_knot_order(const Spline& spline, uint16_t first, uint16_t last) {
  for (uint16_t i = first; i < last; ++i) {
    if (spline.knot[i + 1] < spline.knot[i]) return GeometryError::kKnotsDecreasing;
  }
  return GeometryError::kOk;
}

GeometryError check_points(const Spline& spline, uint16_t first, uint16_t last) {
  for (uint16_t i = first; i <= last; ++i) {
    const ControlPoint& c = spline.control[i];
    if (c.x_um > kMaxCoordinateUm || c.x_um < -kMaxCoordinateUm || c.y_um > kMaxCoordinateUm ||
        c.y_um < -kMaxCoordinateUm)
      return GeometryError::kCoordinateOutOfRange;
    if (spline.rational && c.weight_q14 == 0) return GeometryError::kZeroWeight;
  }
  return GeometryError::kOk;
}

// Checks, in order: degree, counts, knot order, non-empty domain, coordinates, weights.
// The order is part of the contract (one code per spline, the first problem found).
GeometryError check_shape(const Spline& spline) {
  const uint16_t p = spline.degree;
  if (p == 0 || p > kMaxDegree) return GeometryError::kDegreeUnsupported;
  if (spline.control_count > kMaxControlPoints) return GeometryError::kTooManyControlPoints;
  if (spline.control_count < p + 1) return GeometryError::kTooFewControlPoints;
  if (spline.knot_count != spline.control_count + p + 1) return GeometryError::kKnotCountMismatch;
  return GeometryError::kOk;
}

GeometryError validate_spline(const Spline& spline) {
  const uint16_t p = spline.degree;
  GeometryError e = check_shape(spline);
  if (e != GeometryError::kOk) return e;
  e = check_knot_order(spline, 0, (uint16_t)(spline.knot_count - 1U));
  if (e != GeometryError::kOk) return e;
  // The curve lives on [knot[p], knot[n]]; it needs one span of positive length there.
  if (spline.knot[spline.control_count] == spline.knot[p]) return GeometryError::kKnotRangeEmpty;
  e = check_points(spline, 0, (uint16_t)(spline.control_count - 1U));
  if (e != GeometryError::kOk) return e;
  // kKnotSpanTooLong is never returned: knot differences are taken as 32-bit unsigned
  // values and normalised per span in 64-bit arithmetic, so any int32 range works.
  return GeometryError::kOk;
}

}  // namespace core
