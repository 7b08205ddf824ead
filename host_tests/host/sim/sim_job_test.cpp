// Jobs through the simulated machine over real loopback TCP: clean, noisy, held, aborted.
// The firmware is the real application on the TMC428 model; time is virtual.
#include <gtest/gtest.h>

#include <cmath>  // M_PI

#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/cut_path.h"
#include "host_tests/host/sim/faulty_link.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using test::circle_curve;
using test::drawing_of;
using test::line_curve;
using test::plan_of;
using test::s_curve;

sim::SimJobOptions fast_options() {
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(2);
  return o;
}

// First and last pen-down sample times (ms) of a trace.
std::pair<uint64_t, uint64_t> cut_window(const sim::SimJobResult& r, const JobPlan& plan) {
  const std::vector<bool> down = test::pen_down_samples(r.trace, plan);
  uint64_t first = 0, last = 0;
  for (size_t i = 0; i < r.trace.size(); ++i) {
    if (!down[i]) continue;
    if (first == 0) first = r.trace[i].t_ms;
    last = r.trace[i].t_ms;
  }
  return {first, last};
}

TEST(SimJob, CleanLinkCompletesAndFollowsTheCurves) {
  const JobPlan plan =
      plan_of(drawing_of({circle_curve(20, 20, 10), s_curve(40, 20), line_curve(0, 0, 30, 5)}));
  const sim::SimJobResult r = sim::run_sim_job(plan, fast_options());
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_LE(r.max_contour_error_um, 10.0);
  EXPECT_EQ(r.stats.retransmits, 0u);
  EXPECT_NEAR(r.cut_mm, plan.cut_length_mm, 0.01 * plan.cut_length_mm);
}

TEST(SimJob, CircleTakesAtMostTenPercentOverLengthOverFeed) {
  const double radius_mm = 20, feed_mm_s = 10;
  const JobPlan plan = plan_of(drawing_of({circle_curve(30, 30, radius_mm)}), feed_mm_s);
  const sim::SimJobResult r = sim::run_sim_job(plan, fast_options());
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  const auto w = cut_window(r, plan);
  const double cut_s = (w.second - w.first) / 1000.0;
  const double ideal_s = 2 * M_PI * radius_mm / feed_mm_s;
  EXPECT_LE(cut_s, 1.1 * ideal_s);
  EXPECT_GE(cut_s, 0.99 * ideal_s);  // never faster than the feed
}

TEST(SimJob, NoisyLinkLosesAndRepeatsNothing) {
  const JobPlan plan = plan_of(drawing_of({circle_curve(20, 20, 8), s_curve(40, 20)}));
  const sim::SimJobResult clean = sim::run_sim_job(plan, fast_options());
  ASSERT_EQ(clean.outcome, JobOutcome::kCompleted) << clean.message;

  sim::SimJobOptions o = fast_options();
  test::Faults f;
  f.flip_bit = 0.003;
  f.drop_byte = 0.002;
  f.garbage = 0.05;
  f.drop_frame = 0.03;
  f.seed = 7;
  o.wrap_link = [f](std::unique_ptr<Link> inner) -> std::unique_ptr<Link> {
    return std::make_unique<test::FaultyLink>(std::move(inner), f);
  };
  const sim::SimJobResult noisy = sim::run_sim_job(plan, o);
  ASSERT_EQ(noisy.outcome, JobOutcome::kCompleted) << noisy.message;
  EXPECT_GT(noisy.stats.retransmits, 0u);
  EXPECT_LE(noisy.max_contour_error_um, 10.0);
  // A lost segment shortens the cut path, one executed twice lengthens it.
  EXPECT_NEAR(noisy.cut_mm, clean.cut_mm, 0.002 * clean.cut_mm);
  EXPECT_NEAR(noisy.rapid_mm, clean.rapid_mm, 0.002 * clean.rapid_mm + 0.01);
}

TEST(SimJob, HoldStopsTheToolAndResumeFinishesTheJob) {
  const JobPlan plan = plan_of(drawing_of({circle_curve(20, 20, 10), circle_curve(50, 20, 10)}));
  sim::SimJobOptions o = fast_options();
  bool held_seen = false, resumed = false;
  int held_polls = 0;
  int32_t held_x = 0, held_y = 0;
  bool moved_while_held = false;
  o.on_progress = [&](Sender& s, const Progress& p) {
    if (!held_seen && p.executed * 2 >= p.total) s.request_hold();
    if (p.status.state == proto::MachineState::kHeld && !resumed) {
      if (!held_seen) {
        held_x = p.status.x_um;
        held_y = p.status.y_um;
      }
      moved_while_held |= (p.status.x_um != held_x || p.status.y_um != held_y);
      held_seen = true;
      if (++held_polls == 20) {
        s.request_resume();
        resumed = true;
      }
    }
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_TRUE(held_seen);
  EXPECT_FALSE(moved_while_held);
  EXPECT_LE(r.max_contour_error_um, 10.0);
}

// Two resume requests in a row (two clicks, two API calls): the second finds the machine
// already resumed and must not end the job (a second #R was refused, bad_state, and the job
// failed as if a queued command had been refused).
TEST(SimJob, ASecondResumeRightAfterTheFirstIsHarmless) {
  const JobPlan plan = plan_of(drawing_of({circle_curve(20, 20, 10), circle_curve(50, 20, 10)}));
  sim::SimJobOptions o = fast_options();
  bool held_seen = false;
  int resumes = 0;
  o.on_progress = [&](Sender& s, const Progress& p) {
    if (!held_seen && p.executed * 2 >= p.total) s.request_hold();
    if (p.status.state == proto::MachineState::kHeld) held_seen = true;
    // One request per progress report, so each is taken after the #R before it went out.
    if (held_seen && resumes < 4) {
      s.request_resume();
      ++resumes;
    }
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_TRUE(held_seen);
  EXPECT_EQ(resumes, 4);
  EXPECT_LE(r.max_contour_error_um, 10.0);
}

TEST(SimJob, AbortStopsTheJobAndSaysSo) {
  const JobPlan plan = plan_of(drawing_of({circle_curve(20, 20, 10), circle_curve(50, 20, 10)}));
  sim::SimJobOptions o = fast_options();
  o.on_progress = [](Sender& s, const Progress& p) {
    if (p.executed * 3 >= p.total) s.request_abort();
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  EXPECT_EQ(r.outcome, JobOutcome::kAborted);
  EXPECT_NE(r.message.find("aborted"), std::string::npos);
  EXPECT_LT(r.cut_mm, 0.9 * plan.cut_length_mm);
}

TEST(SimJob, CutLinkEndsTheJobAsLinkLost) {
  const JobPlan plan = plan_of(drawing_of({circle_curve(20, 20, 10), circle_curve(50, 20, 10)}));
  sim::SimJobOptions o = fast_options();
  test::Faults f;
  f.cut_after = 600;
  o.wrap_link = [f](std::unique_ptr<Link> inner) -> std::unique_ptr<Link> {
    return std::make_unique<test::FaultyLink>(std::move(inner), f);
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  EXPECT_EQ(r.outcome, JobOutcome::kLinkLost);
  EXPECT_NE(r.message.find("link cut"), std::string::npos);
}

TEST(SimJob, OutOfTravelJobIsRefusedBeforeAnythingMoves) {
  // The plan's work area is checked on the host; a drawing wider than A4 never starts.
  EXPECT_THROW(plan_of(drawing_of({line_curve(0, 0, 400, 0)})), PlanError);
}

}  // namespace
}  // namespace host
