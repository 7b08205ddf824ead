// core::Spline <-> the compact host-side copy a plan step keeps.
#include "host/lib/plan/step_spline.h"

#include <algorithm>  // std::copy, std::min

namespace host {

StepSpline::StepSpline(const core::Spline& s)
    : degree(s.degree),
      rational(s.rational),
      control(s.control, s.control + std::min<unsigned>(s.control_count, core::kMaxControlPoints)),
      knot(s.knot, s.knot + std::min<unsigned>(s.knot_count, core::kMaxKnots)) {}

core::Spline StepSpline::firmware() const {
  core::Spline s{};
  s.degree = degree;
  s.rational = rational;
  const size_t controls = std::min<size_t>(control.size(), core::kMaxControlPoints);
  const size_t knots = std::min<size_t>(knot.size(), core::kMaxKnots);
  s.control_count = static_cast<uint16_t>(controls);
  s.knot_count = static_cast<uint16_t>(knots);
  std::copy(control.begin(), control.begin() + controls, s.control);
  std::copy(knot.begin(), knot.begin() + knots, s.knot);
  return s;
}

}  // namespace host
