// The time left of a running job (/api/status `remaining_s`): the plan's time shared out over
// its steps, counted down from the step the machine is at, and scaled by how fast the
// machine has been against the plan. Within one step it only falls (or stands still once the
// step's planned time is used up): a long command or a silent link never makes it climb.
#ifndef HOST_LIB_SERVER_TIME_LEFT_H
#define HOST_LIB_SERVER_TIME_LEFT_H

#include <memory>  // std::shared_ptr
#include <vector>  // std::vector

#include "host/lib/plan/job_plan.h"

namespace host::server {

// Estimated run time of any plan from its steps and their own feeds (rapids, plunges,
// dwells, pen moves; a spline by its control polygon).
double planned_seconds_by_steps(const JobPlan& plan);
// The same summed to the end of each step (seconds from the plan's start).
std::vector<float> step_end_seconds(const JobPlan& plan);

class TimeLeft {
 public:
  // A job planned to take `planned_s` (its record's figure), shared out over its steps in
  // the proportions `step_end_s` gives (null or empty: the whole figure, no steps known).
  void plan(std::shared_ptr<const std::vector<float>> step_end_s, double planned_s);
  // This run starts at plan step `first` (a continued job: where it resumes; -1: none left).
  void start_at(int first);
  // The machine is at plan step `step` (-1: past the last; one before this run's first counts
  // as the first) after `working_s` seconds of work in this run. At a new step the
  // machine's pace against the plan is measured again.
  void at_step(int step, double working_s);
  // Seconds left after `working_s` seconds of work in this run (before the cut runs: the
  // planned time from this run's first step, standing still).
  double remaining(double working_s) const;

 private:
  double planned_before(int step) const;  // planned seconds of the steps before `step`
  std::shared_ptr<const std::vector<float>> ends_;
  double scale_ = 1;  // to the record's planned time
  double planned_s_ = 0;
  int first_ = 0;
  bool running_ = false;  // at_step has been called
  int step_ = 0;
  double step_started_s_ = 0;  // working seconds when step_ began
  double pace_ = 1;            // machine seconds per planned second, as measured
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_TIME_LEFT_H
