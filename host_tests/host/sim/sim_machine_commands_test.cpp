// Pause, dwell, spindle and drill steps through the encoder, the sender and the simulated
// machine: the simulated operator confirms the pause, the spindle output is recorded.
#include <gtest/gtest.h>

#include <algorithm>  // std::min

#include "host/lib/sim/sim_job.h"

namespace host {
namespace {

PlanStep step(PlanStep::Kind kind) {
  PlanStep s;
  s.kind = kind;
  return s;
}

PlanStep drill_at(int32_t x_um, int32_t y_um) {
  PlanStep s = step(PlanStep::kDrill);
  s.to = {x_um, y_um};
  s.z_start_um = 500;
  s.z_um = -1000;
  s.feed_um_per_s = 1000;
  return s;
}

// Two holes with a tool change between them, as a PCB drill job plans it.
JobPlan drill_job() {
  JobPlan plan;
  PlanStep up = step(PlanStep::kPenUp);
  up.z_um = 2000;
  PlanStep on = step(PlanStep::kSpindle);
  on.spindle_on = true;
  PlanStep off = step(PlanStep::kSpindle);
  PlanStep run_up = step(PlanStep::kDwell);
  run_up.dwell_ms = 300;
  PlanStep change = step(PlanStep::kPause);
  change.text = "T2 1.0mm drill";
  PlanStep home = step(PlanStep::kRapid);
  plan.steps = {up,     on, run_up, drill_at(10000, 10000), off, up,
                change, on, run_up, drill_at(20000, 10000), off, up,
                home};
  return plan;
}

TEST(SimMachineCommands, DrillJobWithAToolChangeRunsToTheEnd) {
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(2);
  o.machine.pause_confirm_ms = 400;
  const JobPlan plan = drill_job();
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_EQ(r.pauses_confirmed, 1);
  EXPECT_FALSE(r.spindle_on);

  // Both holes reach the bottom; the tool stood still at the travel height for the pause.
  double deepest_first = 1e9, deepest_second = 1e9;
  uint64_t longest_still_ms = 0;
  for (size_t i = 1; i < r.trace.size(); ++i) {
    const sim::ToolSample& s = r.trace[i];
    if (std::abs(s.x_mm - 10) < 0.01) deepest_first = std::min(deepest_first, s.z_mm);
    if (std::abs(s.x_mm - 20) < 0.01) deepest_second = std::min(deepest_second, s.z_mm);
    longest_still_ms = std::max(longest_still_ms, s.t_ms - r.trace[i - 1].t_ms);
  }
  EXPECT_NEAR(deepest_first, -1.0, 0.005);
  EXPECT_NEAR(deepest_second, -1.0, 0.005);
  EXPECT_GE(longest_still_ms, 400u);  // the simulated operator's delay
  EXPECT_NEAR(r.trace.back().x_mm, 0.0, 0.005);
}

}  // namespace
}  // namespace host
