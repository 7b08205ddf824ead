// Float B-spline evaluation, only to compare cycle counts with the fixed-point core on the
// proxy: the textbook De Boor recursion per point, and a Horner polynomial per span.
#ifndef HOST_TESTS_TARGET_PROXY_FLOAT_DEBOOR_H
#define HOST_TESTS_TARGET_PROXY_FLOAT_DEBOOR_H

#include <stdint.h>  // uint8_t, uint16_t

#include "firmware/core/spline.h"  // Spline

namespace proxy {

enum { kFloatMaxControl = 16 };

// A polynomial (non-rational) curve in float, knots relative to the first knot.
struct FloatCurve {
  uint8_t degree;
  uint16_t control_count;
  float knot[kFloatMaxControl + 4];
  float x[kFloatMaxControl];
  float y[kFloatMaxControl];
};

// Copies a non-rational spline of up to kFloatMaxControl points; false if it does not fit.
bool float_curve_from(const core::Spline& spline, FloatCurve* out);

// De Boor's recursion at parameter u (knot units, relative) in span `span`.
void float_deboor_point(const FloatCurve& curve, uint16_t span, float u, float* x, float* y);

// Power-basis coefficients of one cubic span in t in [0, 1] (prepared once per span).
struct FloatCubic {
  float cx[4];
  float cy[4];
};

// Builds the span's polynomial from four De Boor points (t = 0, 1/3, 2/3, 1).
void float_cubic_from(const FloatCurve& curve, uint16_t span, FloatCubic* out);

// Horner evaluation of a prepared cubic span at t in [0, 1].
void float_cubic_point(const FloatCubic& cubic, float t, float* x, float* y);

}  // namespace proxy

#endif  // HOST_TESTS_TARGET_PROXY_FLOAT_DEBOOR_H
