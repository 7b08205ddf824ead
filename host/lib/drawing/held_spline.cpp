// HeldSpline: a straight line as its two ends, any other curve whole.
#include "host/lib/drawing/held_spline.h"

#include <string.h>  // memcmp

#include <utility>  // std::move

namespace host {
namespace {

const double kForwardKnots[4] = {0.0, 0.0, 1.0, 1.0};
const double kBackwardKnots[4] = {-1.0, -1.0, -0.0, -0.0};  // reversed(): negated, the zeros -0

bool knots_are(const std::vector<double>& knots, const double (&want)[4]) {
  return knots.size() == 4 && memcmp(knots.data(), want, sizeof want) == 0;
}

}  // namespace

LineKnots line_knots_of(const BSpline& s) {
  if (s.degree != 1 || s.control.size() != 2 || s.rational()) return LineKnots::kNotALine;
  if (knots_are(s.knots, kForwardKnots)) return LineKnots::kForward;
  if (knots_are(s.knots, kBackwardKnots)) return LineKnots::kBackward;
  return LineKnots::kNotALine;
}

BSpline line_from_ends(const double (&ends)[4], LineKnots knots) {
  BSpline s;
  s.degree = 1;
  s.control = {Point2(ends[0], ends[1]), Point2(ends[2], ends[3])};
  const double* k = knots == LineKnots::kForward ? kForwardKnots : kBackwardKnots;
  s.knots.assign(k, k + 4);
  return s;
}

BSpline HeldSpline::get() const {
  if (knots_ != LineKnots::kNotALine) return line_from_ends(ends_, knots_);
  return curve_ ? *curve_ : BSpline();
}

LineKnots hold_spline(BSpline s, double (&ends)[4], std::shared_ptr<const BSpline>* curve) {
  const LineKnots knots = line_knots_of(s);
  if (knots == LineKnots::kNotALine) {
    ends[0] = ends[1] = ends[2] = ends[3] = 0;
    *curve = std::make_shared<const BSpline>(std::move(s));
  } else {
    ends[0] = s.control[0].x();
    ends[1] = s.control[0].y();
    ends[2] = s.control[1].x();
    ends[3] = s.control[1].y();
    curve->reset();
  }
  return knots;
}

void HeldSpline::set(BSpline s) {
  knots_ = hold_spline(std::move(s), ends_, &curve_);
}

}  // namespace host
