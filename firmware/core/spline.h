// A B-spline as the firmware stores it: degree 1..3, integer knots of any range, control
// points in micrometres, optional rational weights. Fixed capacity, no heap.
#ifndef FIRMWARE_CORE_SPLINE_H
#define FIRMWARE_CORE_SPLINE_H

#include <stdint.h>  // int32_t

#include "firmware/core/geometry_error.h"

namespace core {

enum { kMaxDegree = 3, kMaxControlPoints = 64, kMaxKnots = kMaxControlPoints + kMaxDegree + 1 };

// Largest |coordinate| accepted, in micrometres (+-1 m: far beyond the table, well inside
// the fixed-point headroom of the evaluator).
static const int32_t kMaxCoordinateUm = 1000000L;

// Rational weight 1.0 in Q14 (weights are (0, 4) unsigned Q2.14 on the wire).
static const uint16_t kWeightOneQ14 = 16384U;

struct PointUm {
  int32_t x_um;
  int32_t y_um;
};

struct ControlPoint {
  int32_t x_um;
  int32_t y_um;
  uint16_t weight_q14;  // kWeightOneQ14 when the spline is not rational
};

struct Spline {
  uint8_t degree;
  bool rational;
  uint16_t control_count;
  uint16_t knot_count;
  ControlPoint control[kMaxControlPoints];
  int32_t knot[kMaxKnots];  // arbitrary integer units; only ratios of differences matter
};

// Checks everything the evaluator relies on. kOk means evaluation cannot trap or loop.
GeometryError validate_spline(const Spline& spline);

// The first four checks of validate_spline (degree, counts): kDegreeUnsupported,
// kTooManyControlPoints, kTooFewControlPoints or kKnotCountMismatch.
GeometryError check_shape(const Spline& spline);
// Parts of validate_spline that the span setup runs on its window alone. kKnotsDecreasing
// when knot[i + 1] < knot[i] for an i in [first, last); needs last < knot capacity.
GeometryError check_knot_order(const Spline& spline, uint16_t first, uint16_t last);
// kCoordinateOutOfRange or kZeroWeight (rational only) for the first bad point in
// [first, last], coordinates checked first.
GeometryError check_points(const Spline& spline, uint16_t first, uint16_t last);

}  // namespace core

#endif  // FIRMWARE_CORE_SPLINE_H
