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
  line_knots_ = hold_spline(std::move(spline), ends_, &curve_);
}

}  // namespace host
