// The tool's path through a plan's steps, step by step: one walker for everything that draws
// or follows the planned path (the plot's planned path, the server page's live preview), so
// they agree on what each step moves.
#ifndef HOST_LIB_PLAN_TOOL_PATH_WALK_H
#define HOST_LIB_PLAN_TOOL_PATH_WALK_H

#include <cstddef>     // size_t
#include <functional>  // std::function
#include <vector>      // std::vector

#include "host/lib/plan/job_plan.h"

namespace host {

// What a step does to the tool's place.
enum class StepMove {
  kNone,       // pen up/down, pause, dwell, spindle: no move in X/Y
  kNew,        // a move: a rapid, feed or drill (to its end), or a curve (its samples)
  kContinues,  // a further spline step of the curve the step before began (already drawn)
};

struct ToolMove {
  size_t step = 0;  // index into plan.steps
  StepMove kind = StepMove::kNone;
  bool pen_down = false;          // the pen's state during the move (after a pen step: the new one)
  std::vector<Point2> points_mm;  // kNew: the places it passes, to its end (not its start)
};

// Calls visit once per step, in order. A curve's points are sampled at tol_mm; a curve sent
// as several spline steps is one move, its first step's. A plan starts at the zero, pen up.
void walk_tool_path(const JobPlan& plan, double tol_mm,
                    const std::function<void(const ToolMove&)>& visit);

}  // namespace host

#endif  // HOST_LIB_PLAN_TOOL_PATH_WALK_H
