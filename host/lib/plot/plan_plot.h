// Plot input from a job plan: the planned curves and the planned tool path (pen-down
// curves sampled, pen-up moves straight), in the machine frame.
#ifndef HOST_LIB_PLOT_PLAN_PLOT_H
#define HOST_LIB_PLOT_PLAN_PLOT_H

#include "host/lib/plan/job_plan.h"
#include "host/lib/plot/plot.h"

namespace host {

// Curves sampled at tol_mm (straight lines as their ends); the tool path follows the plan's
// steps unless with_planned_path is false (a simulated path goes there instead).
PlotInput plot_input_from_plan(const JobPlan& plan, const std::string& title, double tol_mm = 0.01,
                               bool with_planned_path = true);

}  // namespace host

#endif  // HOST_LIB_PLOT_PLAN_PLOT_H
