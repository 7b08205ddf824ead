// Coded errors of the geometry core. Values are stable: they travel in protocol replies.
#ifndef FIRMWARE_CORE_GEOMETRY_ERROR_H
#define FIRMWARE_CORE_GEOMETRY_ERROR_H

#include <stdint.h>  // uint8_t

namespace core {

enum class GeometryError : uint8_t {
  kOk = 0,
  kDegreeUnsupported = 1,     // degree 0 or > kMaxDegree
  kTooManyControlPoints = 2,  // over kMaxControlPoints
  kTooFewControlPoints = 3,   // fewer than degree + 1
  kKnotCountMismatch = 4,     // knots != control points + degree + 1
  kKnotsDecreasing = 5,       // knot[i+1] < knot[i]
  kKnotRangeEmpty = 6,        // no span of positive length in the valid range
  kKnotSpanTooLong = 7,       // a span longer than the fixed-point normalisation allows
  kCoordinateOutOfRange = 8,  // a control point outside kMaxCoordinateUm
  kZeroWeight = 9,            // a rational weight of zero
  kToleranceInvalid = 10,     // step tolerance or resolution of zero
  kOffsetTooLarge = 11        // tool offset larger than the curve's radius of curvature allows
};

}  // namespace core

#endif  // FIRMWARE_CORE_GEOMETRY_ERROR_H
