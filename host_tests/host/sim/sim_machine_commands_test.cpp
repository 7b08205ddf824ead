// Pause, dwell, spindle and drill steps through the encoder, the sender and the simulated
// machine: the simulated operator confirms the pause, the spindle output is recorded.
#include <gtest/gtest.h>

#include <algorithm>  // std::min
#include <cmath>      // std::hypot
#include <cstdio>     // std::printf

#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/cut_path.h"
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
  change.set_text("T2 1.0mm drill");
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

// A tool-radius offset runs on the controller: the pen-down path of a 10 mm circle traced
// with a 0.3 mm offset lies 0.3 mm off the circle all the way round (after the lead-in from
// the plunge point on the curve).
TEST(SimMachineCommands, CircleWithAToolOffsetIsCutBesideTheCircle) {
  JobPlan plan = test::plan_of(test::drawing_of({test::circle_curve(30, 30, 10)}));
  int offset_steps = 0;
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    if (plan.steps[i].kind == PlanStep::kSpline) {
      plan.steps.edit(i, [](PlanStep& s) { s.tool_offset_um = 300; });
      ++offset_steps;
    }
  }
  ASSERT_GT(offset_steps, 0);
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(2);
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  const std::vector<bool> down = test::pen_down_samples(r.trace, plan);
  const double cx = (plan.extents_mm.min.x() + plan.extents_mm.max.x()) / 2;  // machine frame
  const double cy = (plan.extents_mm.min.y() + plan.extents_mm.max.y()) / 2;
  std::vector<double> radii;
  for (size_t i = 1; i < r.trace.size(); ++i) {
    const sim::ToolSample& a = r.trace[i - 1];
    const sim::ToolSample& b = r.trace[i];
    const bool cutting = down[i] && down[i - 1] && (a.x_mm != b.x_mm || a.y_mm != b.y_mm);
    if (cutting) radii.push_back(std::hypot(b.x_mm - cx, b.y_mm - cy));
  }
  ASSERT_GT(radii.size(), 100u);
  std::sort(radii.begin(), radii.end());
  const double median = radii[radii.size() / 2];
  size_t beside = 0;
  for (double d : radii) beside += std::abs(d - median) < 0.01 ? 1 : 0;
  std::printf(
      "[ metrics  ] offset circle: median radius %.4f mm, %zu of %zu pen-down samples "
      "(moving in X/Y) within 10 um of it (10 mm circle, 0.3 mm offset)\n",
      median, beside, radii.size());
  // One side of the circle (inside or outside, by the direction it is drawn), all the way
  // round; only the lead-in from the plunge point on the curve to the offset start is not.
  EXPECT_NEAR(std::abs(median - 10.0), 0.3, 0.005);
  EXPECT_GE(beside, radii.size() * 95 / 100);
  EXPECT_GE(radii.front(), 9.7 - 0.01);
  EXPECT_LE(radii.back(), 10.3 + 0.01);
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
