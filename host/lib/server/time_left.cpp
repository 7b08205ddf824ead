// A running job's time left (time_left.h).
#include "host/lib/server/time_left.h"

#include <algorithm>  // std::min, std::max, std::clamp
#include <cmath>      // std::hypot, std::abs

#include "firmware/config/machine_config.h"

namespace host::server {

namespace {

// The planned time of `plan`, step by step: at_end(seconds so far) after each step.
// A spline step's length: its control polygon's (the curve is no longer; on the fine fits of
// isolation contours it is close). Its chord was 0 for a closed contour (an outside tester
// saw the time left stand still for 17 s of cutting, then jump by 175 s).
double spline_length_mm(const PlanStep& s, double from_x_mm, double from_y_mm) {
  double len = 0, x = from_x_mm, y = from_y_mm;
  for (const core::ControlPoint& p : s.spline().control) {
    len += std::hypot(p.x_um / 1000.0 - x, p.y_um / 1000.0 - y);
    x = p.x_um / 1000.0, y = p.y_um / 1000.0;
  }
  return len;
}

// The tool's place and the seconds so far, one step after another.
class StepClock {
 public:
  StepClock() {
    const config::MachineConfig m = config::default_machine_config();
    rapid_mm_s_ = m.rapid_feed_um_per_s / 1000.0;
    z_mm_s_ = m.axis[config::kAxisZ].max_speed_um_per_s / 1000.0;
  }
  void add(const PlanStep& s) {
    const double tx = s.to.x_um / 1000.0, ty = s.to.y_um / 1000.0;
    const double d = std::hypot(tx - x, ty - y);
    const double feed = s.feed_um_per_s > 0 ? s.feed_um_per_s / 1000.0 : rapid_mm_s_;
    switch (s.kind) {
      case PlanStep::kRapid:
        seconds += d / rapid_mm_s_;
        x = tx, y = ty;
        break;
      case PlanStep::kFeed:
        seconds += d / feed;
        x = tx, y = ty;
        break;
      case PlanStep::kSpline:
        seconds += spline_length_mm(s, x, y) / feed;
        x = tx, y = ty;
        break;
      case PlanStep::kDrill: {
        const double start = s.z_start_um / 1000.0, bottom = s.z_um / 1000.0;
        seconds += d / rapid_mm_s_ + std::abs(z - start) / z_mm_s_ + 2 * (start - bottom) / feed;
        x = tx, y = ty, z = start;
        break;
      }
      case PlanStep::kPenUp:
      case PlanStep::kPenDown:
        seconds += std::abs(s.z_um / 1000.0 - z) / std::min(z_mm_s_, feed);
        z = s.z_um / 1000.0;
        break;
      case PlanStep::kDwell:
        seconds += s.dwell_ms / 1000.0;
        break;
      case PlanStep::kPause:
      case PlanStep::kSpindle:
        break;
    }
  }
  double x = 0, y = 0, z = 0, seconds = 0;

 private:
  double rapid_mm_s_ = 0, z_mm_s_ = 0;
};

constexpr size_t kStepsAMark = 64;

}  // namespace

double planned_seconds_by_steps(const JobPlan& plan) {
  StepClock clock;
  for (const PlanStep& s : plan.steps) clock.add(s);
  return clock.seconds;
}

PlannedTimes::PlannedTimes(const std::shared_ptr<const JobPlan>& plan)
    : plan_(plan), size_(plan->steps.size()) {
  StepClock clock;
  size_t i = 0;
  marks_.reserve(size_ / kStepsAMark + 1);
  for (const PlanStep& s : plan->steps) {
    if (i++ % kStepsAMark == 0) marks_.push_back({clock.seconds, clock.x, clock.y, clock.z});
    clock.add(s);
  }
  total_s_ = clock.seconds;
}

double PlannedTimes::end_s(size_t step) const {
  const std::shared_ptr<const JobPlan> plan = plan_.lock();
  if (!plan) return total_s_;
  const Mark& m = marks_[step / kStepsAMark];
  StepClock clock;
  clock.seconds = m.seconds, clock.x = m.x_mm, clock.y = m.y_mm, clock.z = m.z_mm;
  for (size_t i = step / kStepsAMark * kStepsAMark; i <= step; ++i) clock.add(plan->steps[i]);
  return clock.seconds;
}

void TimeLeft::plan(std::shared_ptr<const PlannedTimes> steps, double planned_s) {
  ends_ = std::move(steps);
  planned_s_ = planned_s;
  const double total = ends_ && ends_->size() > 0 ? ends_->total_s() : 0.0;
  if (total <= 0) ends_.reset();
  scale_ = total > 0 ? planned_s / total : 1.0;
  first_ = step_ = 0;
  running_ = false;
  step_started_s_ = 0;
  pace_ = 1;
}

void TimeLeft::start_at(int first) {
  first_ = step_ = first;
  running_ = false;
}

double TimeLeft::planned_before(int step) const {
  if (!ends_ || !ends_->readable()) return step < 0 ? planned_s_ : 0.0;
  if (step < 0 || static_cast<size_t>(step) > ends_->size()) return planned_s_;
  return step == 0 ? 0.0 : ends_->end_s(static_cast<size_t>(step) - 1) * scale_;
}

void TimeLeft::at_step(int step, double working_s) {
  if (step >= 0) step = std::max(step, first_);  // a resume's way back: before this run's part
  if (running_ && step == step_) return;
  running_ = true;
  step_ = step;
  step_started_s_ = working_s;
  // The pace so far, trusted as more of this run's plan is done (the first steps, with the
  // zeroing and the map's frames, say little); kept within 4x either way.
  const double run_s = planned_s_ - planned_before(first_);
  const double done_s = planned_before(step) - planned_before(first_);
  if (done_s <= 0 || run_s <= 0) return;
  const double measured = std::clamp(working_s / done_s, 0.25, 4.0);
  const double trust = std::min(1.0, done_s / (0.1 * run_s));
  pace_ = 1.0 + trust * (measured - 1.0);
}

double TimeLeft::remaining(double working_s) const {
  if (!running_) return planned_s_ - planned_before(first_);
  if (step_ < 0) return 0.0;
  const double step_s = planned_before(step_ + 1) - planned_before(step_);
  const double into_step_s = std::clamp((working_s - step_started_s_) / pace_, 0.0, step_s);
  return std::max(0.0, (planned_s_ - planned_before(step_) - into_step_s) * pace_);
}

}  // namespace host::server
