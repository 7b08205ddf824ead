// The plan's compact step list: every step comes back as it was given, whatever its kind,
// while a job of separate lines is held in 16 bytes a step.
#include "host/lib/plan/step_list.h"

#include <gtest/gtest.h>

#include <vector>  // std::vector

#include "host/lib/drawing/conics.h"
#include "host/lib/plan/firmware_spline.h"

namespace host {
namespace {

PlanStep step(PlanStep::Kind kind, int32_t x, int32_t y, int curve) {
  PlanStep s;
  s.kind = kind;
  s.to = core::PointUm{x, y};
  s.curve = curve;
  return s;
}

// One of each kind, with every field that kind reads set to something other than its default.
std::vector<PlanStep> every_kind() {
  std::vector<PlanStep> v;
  PlanStep up = step(PlanStep::kPenUp, 0, 0, -1);
  up.z_um = 2000;
  v.push_back(up);
  PlanStep on = step(PlanStep::kSpindle, 0, 0, -1);
  on.spindle_on = true;
  v.push_back(on);
  v.push_back(step(PlanStep::kRapid, 1000, -2000, 0));
  PlanStep down = step(PlanStep::kPenDown, 0, 0, 0);
  down.z_um = -100;
  down.feed_um_per_s = 2000;
  v.push_back(down);
  PlanStep feed = step(PlanStep::kFeed, 3000, 4000, 0);
  feed.feed_um_per_s = 10000;
  feed.tool_offset_um = -150;
  v.push_back(feed);
  PlanStep spline = step(PlanStep::kSpline, 5000, 6000, 1);
  spline.feed_um_per_s = 10000;
  spline.set_spline(StepSpline(to_firmware_splines(line_spline({3, 4}, {5, 6})).front()));
  v.push_back(spline);
  PlanStep pause = step(PlanStep::kPause, 0, 0, -1);
  pause.set_text("T2 1.0mm drill");
  v.push_back(pause);
  PlanStep dwell = step(PlanStep::kDwell, 0, 0, -1);
  dwell.dwell_ms = 1500;
  v.push_back(dwell);
  PlanStep drill = step(PlanStep::kDrill, 7000, 8000, 2);
  drill.z_um = -1800;
  drill.z_start_um = 500;
  drill.feed_um_per_s = 1000;
  v.push_back(drill);
  return v;
}

void expect_same(const PlanStep& a, const PlanStep& b, size_t i) {
  EXPECT_EQ(a.kind, b.kind) << "step " << i;
  EXPECT_EQ(a.spindle_on, b.spindle_on) << "step " << i;
  EXPECT_EQ(a.to.x_um, b.to.x_um) << "step " << i;
  EXPECT_EQ(a.to.y_um, b.to.y_um) << "step " << i;
  EXPECT_EQ(a.z_um, b.z_um) << "step " << i;
  EXPECT_EQ(a.feed_um_per_s, b.feed_um_per_s) << "step " << i;
  EXPECT_EQ(a.tool_offset_um, b.tool_offset_um) << "step " << i;
  EXPECT_EQ(a.dwell_ms, b.dwell_ms) << "step " << i;
  EXPECT_EQ(a.curve, b.curve) << "step " << i;
  EXPECT_EQ(&a.spline(), &b.spline()) << "step " << i;  // shared, not copied
  EXPECT_EQ(a.text(), b.text()) << "step " << i;
}

TEST(StepList, EveryStepComesBackAsItWasGiven) {
  const std::vector<PlanStep> given = every_kind();
  StepList list;
  // Twice over, with other targets the second time: shapes are shared, targets are not.
  for (int round = 0; round < 2; ++round) {
    for (PlanStep s : given) {
      s.to.x_um += round * 11;
      list.push_back(s);
    }
  }
  ASSERT_EQ(list.size(), 2 * given.size());
  for (size_t i = 0; i < list.size(); ++i) {
    PlanStep want = given[i % given.size()];
    want.to.x_um += static_cast<int32_t>(i / given.size()) * 11;
    expect_same(list[i], want, i);
  }
  size_t i = 0;
  for (const PlanStep& s : list) {
    expect_same(s, list[i], i);
    ++i;
  }
  EXPECT_EQ(i, list.size());
}

TEST(StepList, StepsAreChangedInsertedAndErasedInPlace) {
  StepList list = {step(PlanStep::kRapid, 1, 2, 0), step(PlanStep::kFeed, 3, 4, 0)};
  list.edit(1, [](PlanStep& s) { s.feed_um_per_s = 777; });
  EXPECT_EQ(list[1].feed_um_per_s, 777);
  EXPECT_EQ(list[1].to.x_um, 3);
  EXPECT_EQ(list[0].feed_um_per_s, 0);  // its neighbour kept its own shape
  list.insert(list.begin(), step(PlanStep::kPause, 0, 0, -1));
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list.front().kind, PlanStep::kPause);
  EXPECT_EQ(list[1].kind, PlanStep::kRapid);
  list.erase(list.begin());
  EXPECT_EQ(list.front().kind, PlanStep::kRapid);
  EXPECT_EQ(list.back().feed_um_per_s, 777);
  EXPECT_THROW(list[2], std::out_of_range);
}

TEST(StepList, StepsThatDifferOnlyInTargetAndCurveTakeSixteenBytesEach) {
  StepList list;
  const int lines = 10000;
  list.reserve(4 * lines);
  for (int i = 0; i < lines; ++i) {  // lift, travel, plunge, feed: a job of separate lines
    PlanStep up = step(PlanStep::kPenUp, 0, 0, i);
    up.z_um = 2000;
    list.push_back(up);
    list.push_back(step(PlanStep::kRapid, i, 2 * i, i));
    PlanStep down = step(PlanStep::kPenDown, 0, 0, i);
    down.z_um = -100;
    down.feed_um_per_s = 2000;
    list.push_back(down);
    PlanStep feed = step(PlanStep::kFeed, i + 5, 2 * i, i);
    feed.feed_um_per_s = 10000;
    list.push_back(feed);
  }
  // 40-byte PlanSteps in a vector were 160 bytes a line.
  EXPECT_LE(list.heap_bytes(), 16u * 4 * lines + 4 * sizeof(PlanStep));
  EXPECT_EQ(list[4 * 123 + 1].to.y_um, 246);
}

}  // namespace
}  // namespace host
