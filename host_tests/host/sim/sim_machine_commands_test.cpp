// Pause, dwell, spindle and drill steps through the encoder, the sender and the simulated
// machine: the simulated operator confirms the pause, the spindle output is recorded.
#include <gtest/gtest.h>

#include <algorithm>  // std::min

#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

// Drops exactly one ordered frame: the n-th write that is not #? / #I / real-time.
class DropOneFrame : public Link {
 public:
  DropOneFrame(std::unique_ptr<Link> inner, int n) : inner_(std::move(inner)), n_(n) {}
  void write(const uint8_t* data, size_t size) override {
    const bool ordered = size > 1 && data[0] == '#' && data[1] != '?' && data[1] != 'I' &&
                         proto::command_kind(data[1]) == proto::FrameKind::kQueued;
    if (ordered && ++seen_ == n_) return;
    inner_->write(data, size);
  }
  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    return inner_->read(buffer, capacity, timeout);
  }
  std::string name() const override { return inner_->name(); }

 private:
  std::unique_ptr<Link> inner_;
  int n_;
  int seen_ = 0;
};

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

// Many small curves: more splines than the controller's 2 spline slots at any time. The *O
// and *? spline room (v2) keeps the sender from ever being told busy.
TEST(SimMachineCommands, ManySplinesAreSentWithoutBusyOrResends) {
  std::vector<Curve> curves;
  for (int i = 0; i < 12; ++i)
    curves.push_back(test::circle_curve(15 + 12 * (i % 6), 15 + 12 * (i / 6), 4));
  const JobPlan plan = test::plan_of(test::drawing_of(curves));
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(2);
  std::chrono::milliseconds rtt{-1};
  o.on_progress = [&](Sender& sender, const Progress&) { rtt = sender.smoothed_rtt(); };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_EQ(r.stats.retransmits, 0u);
  EXPECT_EQ(r.stats.error_replies, 0u);
  // Acks of frames sent once fed the retransmission timer (it starts at a 50 ms guess).
  EXPECT_GE(rtt.count(), 0);
  EXPECT_NE(rtt.count(), 50);
}

// One lost frame: the frames behind it each answer seq_gap naming the same expected seq; the
// sender goes back once, so at most one window is resent.
TEST(SimMachineCommands, OneLostFrameCostsAtMostOneWindowOfResends) {
  std::vector<Curve> curves;
  for (int i = 0; i < 6; ++i) curves.push_back(test::circle_curve(20 + 15 * i, 30, 5));
  const JobPlan plan = test::plan_of(test::drawing_of(curves));
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(20);
  o.wrap_link = [](std::unique_ptr<Link> inner) -> std::unique_ptr<Link> {
    return std::make_unique<DropOneFrame>(std::move(inner), 12);
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_GE(r.stats.retransmits, 1u);
  EXPECT_LE(r.stats.retransmits, static_cast<size_t>(proto::kWindowFrames));
}

}  // namespace
}  // namespace host
