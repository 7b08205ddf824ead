// One knot span of a B-spline converted once into a span-relative power-basis polynomial
// (De Boor / blossoming done in the setup), so that one point costs a few 32x16 products.
#ifndef FIRMWARE_CORE_SPAN_EVALUATOR_H
#define FIRMWARE_CORE_SPAN_EVALUATOR_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/core/fixed_point.h"     // q6_um_t, q27_t, uq16_t
#include "firmware/core/geometry_error.h"  // GeometryError
#include "firmware/core/spline.h"          // Spline, PointUm

namespace core {

// Curve domain of a validated spline: spans first_span..last_span (knot indices i with
// knot[i] < knot[i+1]; zero-length spans in between are skipped by next_span()).
// first_span() is the first non-empty span at or after index degree.
uint16_t first_span(const Spline& spline);
// One past the last span index usable (control_count).
inline uint16_t span_end(const Spline& spline) {
  return spline.control_count;
}
// Next non-empty span after span, or span_end() when there is none.
uint16_t next_span(const Spline& spline, uint16_t span);

// Derivative direction at a point, scaled so that both components fit in 16 bits
// (|dx|, |dy| < 2^14) without losing the direction. Zero vector if degenerate.
struct Direction {
  int16_t dx;
  int16_t dy;
};

// A point in micrometres with 6 fraction bits (|v| < 2^31 / 64 um = 33.5 m).
struct PointQ6 {
  q6_um_t x_q6;
  q6_um_t y_q6;
};

// Rounds a q6 point to whole micrometres (ties up). Inline: the firmware rounds in one
// place (the walker's emit), where a call and its frame were 0.1 kB on the AVR proxy.
inline PointUm round_point(const PointQ6& p) {
  PointUm r;
  r.x_um = (p.x_q6 + 32) >> kQ6Shift;
  r.y_um = (p.y_q6 + 32) >> kQ6Shift;
  return r;
}

// SpanEvaluator: the span [knot[i], knot[i+1]) as
//   P(t) = origin + (c[0] + c[1] t + c[2] t^2 + c[3] t^3) / 2^6        (polynomial)
//   P(t) = origin + N(t) / W(t)  with N in q6_um and W in q27           (rational)
// t in [0, 1) as uq16 (t = 0 the span start; the span end t = 1 is end_point()).
// Setup (setup()) does the De Boor/blossom work in 64-bit integer arithmetic with
// divisions by knot differences (never zero: the span has positive length and every
// denominator spans it). Per point: 3 (degree 3) 32x16 products per coordinate, Horner;
// no 64-bit arithmetic and no 32/32 division (a ctest checks the generated code).
// A rational point adds W (3 products), one reciprocal of W (one 32/16 division, four
// 16x16 products) and four 16x16 products per coordinate (core/divide.h).
// Error budget: docs/core-math.md (<= 0.1 um for polynomial spans over |coord| <= 1e6).
class SpanEvaluator {
 public:
  SpanEvaluator();

  // Prepares span index `span` (degree <= span < control_count, knot[span] < knot[span+1]);
  // otherwise kKnotRangeEmpty and the evaluator is unset. The span's own window of knots,
  // control points and weights is checked too (the codes of validate_spline), so an
  // unvalidated spline cannot make it divide by zero or read out of bounds.
  GeometryError setup(const Spline& spline, uint16_t span);

  // Point at parameter t (t = 0 gives start_point()).
  PointUm evaluate(uq16_t t) const { return round_point(evaluate_q6(t)); }
  // The same point before rounding (q6 um); t = 65536 gives the end point.
  PointQ6 evaluate_q6(uint32_t t_q16) const;
  // Derivative direction dP/dt at t (only the direction is meaningful).
  Direction direction(uq16_t t) const;
  // Exact span ends (the De Boor values at knot[span] and knot[span+1], rounded to 1 um).
  PointUm start_point() const { return round_point(start_); }
  PointQ6 start_q6() const { return start_; }
  PointUm end_point() const { return round_point(end_); }
  // Derivative direction at the span end (t = 1).
  Direction end_direction() const { return end_dir_; }
  // Taylor coefficients of a polynomial span about t0 over a step h (uq16, t0 < 1,
  // t0 + h <= 1): P(t0 + h s) = P(t0) + a1 s + a2 s^2 + a3 s^3 with a2, a3 in q6 um
  // (|.| < 2^30). False (nothing written) for rational spans and for spans whose
  // coefficients are too large for that bound.
  bool step_bend_q6(uint32_t t0_q16, uint32_t h_q16, PointQ6* a2, PointQ6* a3) const;
  uint8_t degree() const { return degree_; }
  bool rational() const { return rational_; }

 private:
  PointQ6 rational_q6(uq16_t t) const;
  int32_t derivative_at(const q6_um_t* c, uq16_t t) const;

  uint8_t degree_;
  bool rational_;
  PointUm origin_;     // first Bezier point of the span, rounded to 1 um
  PointQ6 origin_q6_;  // the same in q6 (added to every point)
  PointQ6 start_;
  PointQ6 end_;
  q6_um_t cx_[kMaxDegree + 1];  // power-basis coefficients of x (or of w*x) relative
  q6_um_t cy_[kMaxDegree + 1];  // to origin_, in q6 um
  q27_t cw_[kMaxDegree + 1];    // power-basis coefficients of the weight (rational only)
  // Derivative at t = 1, kept at setup so end_direction() costs nothing.
  Direction end_dir_;
  uint8_t dir_shift_;  // fraction bits dropped from the derivative coefficients (0..3)
};

}  // namespace core

#endif  // FIRMWARE_CORE_SPAN_EVALUATOR_H
