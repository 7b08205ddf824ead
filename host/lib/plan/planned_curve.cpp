// PlannedCurve's storage: a straight line as its two ends, any other curve whole (the
// drawing's HeldSpline rules, packed with the curve's flags).
#include <utility>  // std::move

#include "host/lib/plan/job_plan.h"

namespace host {

BSpline PlannedCurve::spline() const {
  if (line_knots_ == LineKnots::kNotALine) return curve_ ? *curve_ : BSpline();
  return line_from_ends(ends_, line_knots_);
}

void PlannedCurve::set_spline(BSpline spline) {
  line_knots_ = line_knots_of(spline);
  if (line_knots_ == LineKnots::kNotALine) {
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
