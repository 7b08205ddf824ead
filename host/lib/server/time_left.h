// The time left of a running job (/api/status `remaining_s`): the plan's time shared out over
// its steps, counted down from the step the machine is at, and scaled by how fast the
// machine has been against the plan. Within one step it only falls (or stands still once the
// step's planned time is used up): a long command or a silent link never makes it climb.
#ifndef HOST_LIB_SERVER_TIME_LEFT_H
#define HOST_LIB_SERVER_TIME_LEFT_H

#include <cstddef>  // size_t
#include <memory>   // std::shared_ptr
#include <vector>   // std::vector

#include "host/lib/plan/job_plan.h"

namespace host::server {

// Estimated run time of any plan from its steps and their own feeds (rapids, plunges,
// dwells, pen moves; a spline by its control polygon).
double planned_seconds_by_steps(const JobPlan& plan);

// The same summed to the end of each step, worked out again from the plan when asked, from a
// mark every 64 steps: a float a step was 16 MB of a million-line job, held while it runs.
// It reads the plan while its owner (the run) keeps it, and does not keep it alive itself:
// an idle machine holds no plan.
class PlannedTimes {
 public:
  explicit PlannedTimes(const std::shared_ptr<const JobPlan>& plan);
  size_t size() const { return size_; }
  // False once the plan is gone (the run has ended).
  bool readable() const { return !plan_.expired(); }
  // Seconds from the plan's start to the end of step `step` (< size()); total_s() once the
  // plan is gone.
  double end_s(size_t step) const;
  double total_s() const { return total_s_; }

 private:
  struct Mark {  // where the tool stands and the seconds so far, before step 64 k
    double seconds = 0, x_mm = 0, y_mm = 0, z_mm = 0;
  };
  std::weak_ptr<const JobPlan> plan_;
  size_t size_ = 0;
  std::vector<Mark> marks_;
  double total_s_ = 0;
};

class TimeLeft {
 public:
  // A job planned to take `planned_s` (its record's figure), shared out over its steps in
  // the proportions `steps` gives (null or no steps: the whole figure, no steps known).
  void plan(std::shared_ptr<const PlannedTimes> steps, double planned_s);
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
  std::shared_ptr<const PlannedTimes> ends_;
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
