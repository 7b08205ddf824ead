// A firmware spline as a plan step keeps it: only the control points and knots it uses.
// core::Spline holds room for the most a controller slot takes (about 1.1 kB); a job of
// a million steps with one inline in each step held gigabytes, most of it for steps that
// have no curve at all (feeds, rapids, pen moves).
#ifndef HOST_LIB_PLAN_STEP_SPLINE_H
#define HOST_LIB_PLAN_STEP_SPLINE_H

#include <stdint.h>  // uint8_t, int32_t

#include <vector>  // std::vector

#include "firmware/core/spline.h"

namespace host {

struct StepSpline {
  uint8_t degree = 0;
  bool rational = false;
  std::vector<core::ControlPoint> control;  // control_count entries
  std::vector<int32_t> knot;                // knot_count entries

  StepSpline() = default;
  // Copies the used part of `s` (control_count and knot_count must be within the arrays).
  explicit StepSpline(const core::Spline& s);
  // The firmware form (what the controller's slot holds), e.g. for validate_spline.
  core::Spline firmware() const;
  bool empty() const { return control.empty(); }
};

}  // namespace host

#endif  // HOST_LIB_PLAN_STEP_SPLINE_H
