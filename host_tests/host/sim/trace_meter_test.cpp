// The trace meter's plot path: thinned to its step, bounded by its budget (the step doubles
// instead), with every pen change kept and the measurements taken on every sample.
#include "host/lib/sim/trace_meter.h"

#include "host/lib/sim/sim_job.h"  // pen_threshold_mm

#include <gtest/gtest.h>

#include <cmath>   // std::abs
#include <vector>  // std::vector

namespace host::sim {
namespace {

// A plan that only sets the pen heights: up at 2 mm, down at -0.1 mm (threshold 0.95 mm).
JobPlan pen_heights_plan() {
  JobPlan plan;
  PlanStep up;
  up.kind = PlanStep::kPenUp;
  up.z_um = 2000;
  PlanStep down;
  down.kind = PlanStep::kPenDown;
  down.z_um = -100;
  plan.steps = {up, down, up};
  return plan;
}

ToolSample at(uint64_t t_ms, double x_mm, double y_mm, double z_mm) {
  return ToolSample{t_ms, x_mm, y_mm, z_mm};
}

bool is_down(const ToolSample& s) {
  return s.z_mm < 0.95;
}

// Pen changes in a path that starts lifted.
int pen_changes(const std::vector<ToolSample>& path) {
  int n = 0;
  for (size_t i = 1; i < path.size(); ++i) n += is_down(path[i]) != is_down(path[i - 1]);
  return n;
}

int pen_changes(const PenPath& path) {
  int n = 0;
  for (size_t i = 1; i < path.size(); ++i) n += path.pen_down(i) != path.pen_down(i - 1);
  return n;
}

TEST(TraceMeter, ALongCutKeepsAtMostItsBudgetWithACoarserStep) {
  TraceMeter m(pen_heights_plan(), 0.01, 1000);
  m.add(at(0, 0, 0, 2.0));
  const int n = 200000;  // 200 mm of cut at 1 um per sample
  for (int i = 0; i <= n; ++i) m.add(at(1 + i, i * 0.001, 0, -0.1));
  m.finish();
  const PenPath& kept = m.path();
  EXPECT_TRUE(m.kept().empty());  // every sample only without a step
  EXPECT_LE(kept.size(), 1000u);
  EXPECT_GE(kept.size(), 250u);  // coarsened only as far as needed
  // The step doubled from 0.01 mm, and the kept samples are that far apart but for the
  // sample that was last at each coarsening (kept, as the path's end then was).
  const double step = m.keep_step_mm();
  const double doublings = std::round(std::log2(step / 0.01));
  EXPECT_GE(doublings, 1.0);
  EXPECT_DOUBLE_EQ(std::exp2(doublings), step / 0.01);
  int short_gaps = 0;
  for (size_t i = 2; i + 1 < kept.size(); ++i)
    short_gaps += kept.point(i).x() - kept.point(i - 1).x() < step - 1e-5;  // float mm
  EXPECT_LE(short_gaps, doublings);
  // Ends kept; the length is measured on every sample, not on the kept ones.
  EXPECT_EQ(kept.point(0).x(), 0.0);
  EXPECT_FLOAT_EQ(kept.point(kept.size() - 1).x(), n * 0.001);
  EXPECT_TRUE(kept.pen_down(kept.size() - 1));
  EXPECT_NEAR(m.cut_mm(), n * 0.001, 1e-6);
  EXPECT_EQ(m.samples(), static_cast<size_t>(n + 2));
}

TEST(TraceMeter, WithoutABudgetEverySampleAStepApartIsKept) {
  TraceMeter m(pen_heights_plan(), 0.01);
  m.add(at(0, 0, 0, 2.0));
  for (int i = 0; i <= 20000; ++i) m.add(at(1 + i, i * 0.001, 0, -0.1));
  m.finish();
  EXPECT_DOUBLE_EQ(m.keep_step_mm(), 0.01);
  // 20 mm at 0.01 mm (0.011 where rounding makes the tenth sample fall just short).
  EXPECT_GE(m.path().size(), 1800u);
  EXPECT_LE(m.path().size(), 2002u);
}

TEST(TraceMeter, CoarseningNeverDropsAPenChange) {
  // 400 short strokes: lift, move, plunge, cut 1 mm in 100 samples. More pen changes than
  // the budget: the budget grows with them instead of dropping any.
  TraceMeter m(pen_heights_plan(), 0.001, 500);
  std::vector<ToolSample> all;
  uint64_t t = 0;
  auto add = [&](const ToolSample& s) {
    all.push_back(s);
    m.add(s);
  };
  add(at(t++, 0, 0, 2.0));
  for (int k = 0; k < 400; ++k) {
    const double y = 0.5 * k;
    add(at(t++, 0, y, 2.0));
    add(at(t++, 0, y, -0.1));
    for (int i = 1; i <= 100; ++i) add(at(t++, i * 0.01, y, -0.1));
    add(at(t++, 1.0, y, 2.0));
  }
  m.finish();
  const PenPath& kept = m.path();
  EXPECT_EQ(pen_changes(kept), pen_changes(all));
  EXPECT_EQ(pen_changes(all), 800);
  EXPECT_LT(kept.size(), all.size() / 10);
  // Every stroke still starts and ends where it did: a cut piece runs from its plunge to the
  // lift (the first pen-up position), and the travel to the next plunge.
  int strokes = 0;
  kept.each_piece([&](const std::vector<Point2>& piece, bool down) {
    if (!down) return;
    EXPECT_EQ(piece.front().x(), 0.0);
    EXPECT_FLOAT_EQ(piece.back().x(), 1.0);
    EXPECT_FLOAT_EQ(piece.back().y(), piece.front().y());
    ++strokes;
  });
  EXPECT_EQ(strokes, 400);
  // Two positions a stroke are all a pen change needs (the last pen-down sample before a
  // lift is where the lift is): fewer than four.
  EXPECT_LT(kept.size(), 4u * 400);
}

// A board's drilling travels from hole to hole at the drill start height (+0.5 mm), far
// below the pen-up height: that travel is not cutting, with or without isolation before it,
// and the top of a holding tab (a pen-up inside the board) is not travel.
TEST(TraceMeter, DrillTravelAtTheStartHeightIsNotCutting) {
  PlanStep up;
  up.kind = PlanStep::kPenUp;
  up.z_um = 2000;
  PlanStep drill;
  drill.kind = PlanStep::kDrill;
  drill.z_start_um = 500;
  drill.z_um = -1800;
  PlanStep iso;
  iso.kind = PlanStep::kPenDown;
  iso.z_um = -50;
  PlanStep cut = iso;
  cut.z_um = -600;
  PlanStep tab_top = up;
  tab_top.z_um = -1300;
  JobPlan drilling;
  drilling.steps = {up, drill, drill};
  EXPECT_DOUBLE_EQ(pen_threshold_mm(drilling), (0.5 - 1.8) / 2);
  JobPlan isolation_and_drilling;
  isolation_and_drilling.steps = {up, iso, up, drill, drill, up};
  EXPECT_DOUBLE_EQ(pen_threshold_mm(isolation_and_drilling), (0.5 - 0.05) / 2);
  JobPlan with_cutout;
  with_cutout.steps = {up, drill, up, cut, tab_top, cut, up};
  EXPECT_DOUBLE_EQ(pen_threshold_mm(with_cutout), (0.5 - 0.6) / 2);
  // Travel between two holes at +0.5 mm: all rapid.
  TraceMeter m(isolation_and_drilling, 0);
  m.add(at(0, 0, 0, 2.0));
  m.add(at(1, 0, 0, 0.5));
  m.add(at(2, 0, 0, -1.8));
  m.add(at(3, 0, 0, 0.5));
  m.add(at(4, 30, 0, 0.5));
  EXPECT_DOUBLE_EQ(m.cut_mm(), 0.0);
  EXPECT_DOUBLE_EQ(m.rapid_mm(), 30.0);
}

// Only the largest contour error is reported: a sample within it of the previous sample's
// nearest segment costs that one segment, not a search; the maximum found is unchanged.
TEST(TraceMeter, SamplesWithinTheLargestErrorSoFarSkipTheSearch) {
  JobPlan plan = pen_heights_plan();
  PlannedCurve line;  // 10 mm along X in 1 000 segments
  BSpline s;
  s.degree = 1;
  for (int i = 0; i <= 1000; ++i) s.control.push_back(Point2(i * 0.01, 0));
  s.knots.assign(s.control.size() + 2, 0.0);
  line.set_spline(s);
  plan.curves.push_back(line);
  TraceMeter m(plan, 0);
  m.add(at(0, 0, 0, 2.0));
  m.add(at(1, 0.005, 0.020, -0.1));  // 20 um off
  const size_t before = m.segments_examined();
  const int n = 9000;  // 9 mm, 1 um off, a sample per um
  for (int i = 0; i < n; ++i) m.add(at(2 + i, 0.006 + i * 0.001, 0.001, -0.1));
  const double per_sample = double(m.segments_examined() - before) / n;
  EXPECT_NEAR(m.max_contour_error_um(), 20.0, 1e-6);
  EXPECT_LT(per_sample, 1.5);
  m.add(at(2 + n, 9.5, -0.030, -0.1));  // 30 um off: still found
  EXPECT_NEAR(m.max_contour_error_um(), 30.0, 1e-6);
  EXPECT_DOUBLE_EQ(m.worst_sample().x_mm, 9.5);
}

// The same along a fine contour (4 um segments, a sample every um): when the tool has left
// the previous nearest segment, the next ones bound it, still without a search.
TEST(TraceMeter, OnAFineContourTheFollowingSegmentsBoundTheError) {
  JobPlan plan = pen_heights_plan();
  PlannedCurve line;
  BSpline s;
  s.degree = 1;
  for (int i = 0; i <= 2500; ++i) s.control.push_back(Point2(i * 0.004, 0));
  s.knots.assign(s.control.size() + 2, 0.0);
  line.set_spline(s);
  plan.curves.push_back(line);
  TraceMeter m(plan, 0);
  m.add(at(0, 0, 0, 2.0));
  m.add(at(1, 0.001, 0.002, -0.1));  // 2 um off
  const size_t before = m.segments_examined();
  const int n = 9000;
  for (int i = 0; i < n; ++i) m.add(at(2 + i, 0.0015 + i * 0.001, -0.001, -0.1));
  const double per_sample = double(m.segments_examined() - before) / n;
  EXPECT_NEAR(m.max_contour_error_um(), 2.0, 1e-6);
  EXPECT_LT(per_sample, 1.6);
}

}  // namespace
}  // namespace host::sim
