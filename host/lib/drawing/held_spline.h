// A curve held as compactly as it allows: a straight line as the DXF import and the
// reversal make it (degree 1, two points, knots 0 0 1 1 or their reversal -1 -1 -0 -0) as
// its two ends, any other curve whole on the heap, shared by copies (never changed once set).
// A million-line drawing held a BSpline with two heap vectors a line (~150 bytes more).
#ifndef HOST_LIB_DRAWING_HELD_SPLINE_H
#define HOST_LIB_DRAWING_HELD_SPLINE_H

#include <stdint.h>  // uint8_t

#include <cstddef>  // size_t
#include <memory>   // std::shared_ptr

#include "host/lib/drawing/bspline.h"

namespace host {

// Which straight line a curve is, if it is one that can be kept as its two ends.
enum class LineKnots : uint8_t { kNotALine, kForward, kBackward };  // 0 0 1 1; -1 -1 -0 -0

// The knots bit for bit, so that the line made again is the curve that was given.
LineKnots line_knots_of(const BSpline& s);
// The line from its ends (x0 y0 x1 y1) and knots (not kNotALine).
BSpline line_from_ends(const double (&ends)[4], LineKnots knots);
// Keeps s as a line's ends (and no curve) or, not a line, as the curve (ends zero): the one
// rule of HeldSpline and PlannedCurve. Returns its knots.
LineKnots hold_spline(BSpline s, double (&ends)[4], std::shared_ptr<const BSpline>* curve);

class HeldSpline {
 public:
  HeldSpline() = default;
  explicit HeldSpline(BSpline s) { set(std::move(s)); }
  // The curve, made from the two ends for a straight line: take it once per use, not per point.
  BSpline get() const;
  void set(BSpline s);
  bool inline_line() const { return knots_ != LineKnots::kNotALine; }
  bool empty() const { return !inline_line() && !curve_; }
  size_t control_count() const { return inline_line() ? 2 : curve_ ? curve_->control.size() : 0; }
  // Calls visit(const Point2&) for each control point, without making the curve again.
  template <class Visit>
  void each_control(Visit visit) const {
    if (inline_line()) {
      visit(Point2(ends_[0], ends_[1]));
      visit(Point2(ends_[2], ends_[3]));
    } else if (curve_) {
      for (const Point2& p : curve_->control) visit(p);
    }
  }

 private:
  double ends_[4] = {0, 0, 0, 0};
  std::shared_ptr<const BSpline> curve_;  // kNotALine: the curve
  LineKnots knots_ = LineKnots::kNotALine;
};

}  // namespace host

#endif  // HOST_LIB_DRAWING_HELD_SPLINE_H
