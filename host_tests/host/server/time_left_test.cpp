// A running job's time left (issue 25's outside tester: it climbed ~10 s a second inside
// one long command and while the link was silent, and a continued run started again from
// the whole job's planned time).
#include <gtest/gtest.h>

#include <memory>   // std::make_shared
#include <utility>  // std::pair

#include "host/lib/server/time_left.h"

namespace host::server {
namespace {

PlanStep dwell_of(uint32_t ms) {
  PlanStep dwell;
  dwell.kind = PlanStep::kDwell;
  dwell.dwell_ms = ms;
  return dwell;
}

// Ten steps of 10 planned seconds each (the record's planned figure 100 s). The plan is kept
// for the whole test program, as a run keeps its plan while it runs.
TimeLeft ten_steps() {
  static const std::shared_ptr<const JobPlan> plan = [] {
    auto p = std::make_shared<JobPlan>();
    for (int i = 1; i <= 10; ++i) p->steps.push_back(dwell_of(10000));
    return p;
  }();
  TimeLeft t;
  t.plan(std::make_shared<const PlannedTimes>(plan), 100.0);
  return t;
}

TEST(TimeLeft, BeforeTheCutItIsThePlannedTimeFromTheFirstStepStandingStill) {
  TimeLeft t = ten_steps();
  EXPECT_DOUBLE_EQ(t.remaining(0), 100.0);
  EXPECT_DOUBLE_EQ(t.remaining(50), 100.0);
  t.start_at(4);  // a continued run: 4 steps cut in earlier runs
  EXPECT_DOUBLE_EQ(t.remaining(0), 60.0);
}

TEST(TimeLeft, NeverRisesWithinAStepHoweverLongItTakes) {
  TimeLeft t = ten_steps();
  t.start_at(0);
  t.at_step(0, 0.0);
  double last = t.remaining(0);
  EXPECT_DOUBLE_EQ(last, 100.0);
  // The step takes 60 s, not 10 (a slow machine, or a silent link): it counts down by the
  // step's planned 10 s, then stands still.
  for (double s = 0.5; s <= 60; s += 0.5) {
    const double now = t.remaining(s);
    EXPECT_LE(now, last) << s;
    last = now;
  }
  EXPECT_DOUBLE_EQ(last, 90.0);
}

TEST(TimeLeft, FollowsTheMachinesPaceOnceEnoughOfThePlanIsDone) {
  TimeLeft t = ten_steps();
  t.start_at(0);
  t.at_step(0, 0.0);
  // The machine takes twice the plan: each step 20 s.
  for (int step = 1; step < 10; ++step) t.at_step(step, 20.0 * step);
  // At the last step, 90 % done at pace 2: 20 s left, counting down in it.
  EXPECT_NEAR(t.remaining(180), 20.0, 1e-9);
  EXPECT_NEAR(t.remaining(190), 10.0, 1e-9);
  t.at_step(-1, 200);
  EXPECT_DOUBLE_EQ(t.remaining(200), 0.0);
}

TEST(TimeLeft, AFirstStepsSlowPaceIsTrustedOnlyAsMoreIsDone) {
  TimeLeft t = ten_steps();
  t.start_at(0);
  t.at_step(0, 0.0);
  // The first 10 % took 4x its plan (zeroing, the map's frames): the pace is capped at 4x
  // and trusted in proportion to the share done, so the next estimate is not 4x the rest.
  t.at_step(1, 40.0);
  EXPECT_LE(t.remaining(40), 4.0 * 90.0);
  EXPECT_GE(t.remaining(40), 90.0);
  TimeLeft early = ten_steps();
  early.start_at(0);
  early.at_step(0, 0.0);
  EXPECT_NEAR(early.remaining(5), 95.0, 1e-9);  // at the plan's pace while nothing is measured
}

TEST(TimeLeft, AContinuedRunMeasuresItsPaceFromWhereItResumed) {
  TimeLeft t = ten_steps();
  t.start_at(5);
  t.at_step(5, 0.0);
  EXPECT_DOUBLE_EQ(t.remaining(0), 50.0);
  t.at_step(6, 10.0);  // at the plan's pace since the resume
  EXPECT_NEAR(t.remaining(10), 40.0, 1e-9);
  // The resume's way back carries earlier steps (the outside tester saw the whole job's time
  // for the first seconds, then a pace from step 0 that made the rest look 4x shorter).
  TimeLeft back = ten_steps();
  back.start_at(5);
  back.at_step(0, 0.0);
  EXPECT_DOUBLE_EQ(back.remaining(0), 50.0);
  back.at_step(6, 10.0);
  EXPECT_NEAR(back.remaining(10), 40.0, 1e-9);
}

TEST(TimeLeft, WithoutStepsItIsTheWholePlannedTime) {
  TimeLeft t;
  t.plan(nullptr, 42.0);
  EXPECT_DOUBLE_EQ(t.remaining(0), 42.0);
}

TEST(TimeLeft, StepEndSecondsSumToThePlansTime) {
  JobPlan plan;
  PlanStep rapid;
  rapid.kind = PlanStep::kRapid;
  rapid.to = {10000, 0};
  PlanStep feed;
  feed.kind = PlanStep::kFeed;
  feed.to = {10000, 20000};
  feed.feed_um_per_s = 5000;
  plan.steps = {rapid, feed, dwell_of(1500)};
  const auto kept = std::make_shared<const JobPlan>(plan);
  const PlannedTimes ends(kept);
  ASSERT_EQ(ends.size(), 3u);
  EXPECT_GT(ends.end_s(0), 0.0);
  EXPECT_NEAR(ends.end_s(1) - ends.end_s(0), 4.0, 1e-9);  // 20 mm at 5 mm/s
  EXPECT_NEAR(ends.end_s(2) - ends.end_s(1), 1.5, 1e-9);
  EXPECT_DOUBLE_EQ(ends.total_s(), planned_seconds_by_steps(plan));
}

// Each step's end is worked out from the mark before it (one every 64 steps): the same
// sums, step by step, as the whole plan's, far into a long job.
TEST(TimeLeft, StepEndsFromTheMarksAreTheRunningSums) {
  JobPlan plan;
  double sum_s = 0;
  std::vector<double> expected;
  for (int i = 0; i < 300; ++i) {
    PlanStep feed;  // 1 mm further along x each step, at 1 to 7 mm/s
    feed.kind = PlanStep::kFeed;
    feed.to = {1000 * (i + 1), 0};
    feed.feed_um_per_s = 1000 * (1 + i % 7);
    plan.steps.push_back(feed);
    sum_s += 1.0 / (1 + i % 7);
    expected.push_back(sum_s);
  }
  const auto kept = std::make_shared<const JobPlan>(plan);
  const PlannedTimes ends(kept);
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(ends.end_s(i), expected[i], 1e-9) << "step " << i;
  }
  EXPECT_NEAR(ends.total_s(), sum_s, 1e-9);
}

// The step times read the plan the run keeps; they do not keep it once the run lets it go
// (an idle machine held a million-line job's plan in its time left), and then the time left
// is the record's planned figure, as with no steps.
TEST(TimeLeft, ThePlanIsNotKeptAliveByItsStepTimes) {
  auto plan = std::make_shared<JobPlan>();
  for (int i = 0; i < 4; ++i) plan->steps.push_back(dwell_of(5000));
  const std::weak_ptr<const JobPlan> seen = plan;
  TimeLeft t;
  t.plan(std::make_shared<const PlannedTimes>(plan), 20.0);
  t.start_at(2);
  EXPECT_DOUBLE_EQ(t.remaining(0), 10.0);  // two of four steps left
  plan.reset();
  EXPECT_TRUE(seen.expired());
  EXPECT_DOUBLE_EQ(t.remaining(0), 20.0);
}

// A closed contour as one spline step (an isolation loop): its time is its length's, not its
// chord's (0: the outside tester's time left stood still while such a loop was cut).
TEST(TimeLeft, AClosedSplineStepTakesTheTimeOfItsLength) {
  JobPlan plan;
  PlanStep loop;
  loop.kind = PlanStep::kSpline;
  loop.feed_um_per_s = 5000;
  StepSpline square;
  square.degree = 1;
  for (const auto& p : {std::pair<int, int>{0, 0}, {20000, 0}, {20000, 20000}, {0, 20000}, {0, 0}})
    square.control.push_back(core::ControlPoint{p.first, p.second, core::kWeightOneQ14});
  square.knot = {0, 0, 1, 2, 3, 4, 4};
  loop.set_spline(square);
  loop.to = {0, 0};
  plan.steps = {loop};
  const auto kept = std::make_shared<const JobPlan>(plan);
  const PlannedTimes ends(kept);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_NEAR(ends.end_s(0), 80.0 / 5.0, 1e-9);  // 80 mm round at 5 mm/s
}

}  // namespace
}  // namespace host::server
