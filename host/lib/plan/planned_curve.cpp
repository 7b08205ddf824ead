// PlannedCurve's storage: a straight line as its two ends, any other curve whole.
#include <string.h>  // memcmp

#include <utility>  // std::move

#include "host/lib/plan/job_plan.h"

namespace host {
namespace {

// The knots of a two-point line as the DXF import makes it, and as reversed() turns them
// (negated end to start: the zeros become -0).
const double kForwardKnots[4] = {0.0, 0.0, 1.0, 1.0};
const double kBackwardKnots[4] = {-1.0, -1.0, -0.0, -0.0};

// Bit for bit, so that the line made again is the curve that was set.
bool knots_are(const std::vector<double>& knots, const double (&want)[4]) {
  return knots.size() == 4 && memcmp(knots.data(), want, sizeof want) == 0;
}

}  // namespace

BSpline PlannedCurve::spline() const {
  if (line_knots_ == kNotALine) return curve_ ? *curve_ : BSpline();
  BSpline s;
  s.degree = 1;
  s.control = {Point2(ends_[0], ends_[1]), Point2(ends_[2], ends_[3])};
  const double* k = line_knots_ == kForward ? kForwardKnots : kBackwardKnots;
  s.knots.assign(k, k + 4);
  return s;
}

void PlannedCurve::set_spline(BSpline spline) {
  const bool two_points = spline.degree == 1 && spline.control.size() == 2 && !spline.rational();
  line_knots_ = !two_points                               ? kNotALine
                : knots_are(spline.knots, kForwardKnots)  ? kForward
                : knots_are(spline.knots, kBackwardKnots) ? kBackward
                                                          : kNotALine;
  if (line_knots_ == kNotALine) {
    ends_[0] = ends_[1] = ends_[2] = ends_[3] = 0;
    curve_ = std::make_shared<const BSpline>(std::move(spline));
  } else {
    ends_[0] = spline.control[0].x();
    ends_[1] = spline.control[0].y();
    ends_[2] = spline.control[1].x();
    ends_[3] = spline.control[1].y();
    curve_.reset();
  }
}

}  // namespace host
