// CurveWalker without offset: point counts, exact ends, the real chord error of the
// adaptive mode against Eigen, and fewer points than uniform stepping on varying curvature.
#include "firmware/core/curve_walker.h"

#include <gtest/gtest.h>

#include <random>

#include "host_tests/core/curve_factory.h"
#include "host_tests/core/curve_walker_helpers.h"

namespace {

using core::GeometryError;

// A curve whose curvature varies a lot: long gentle stretches and one tight hairpin.
core::Spline varying_curvature() {
  return testcurves::clamped_uniform(3, {{0, 0},
                                         {40000, 0},
                                         {80000, 2000},
                                         {100000, 10000},
                                         {100500, 12000},
                                         {99000, 13000},
                                         {60000, 20000},
                                         {20000, 30000},
                                         {0, 60000}});
}

TEST(CurveWalker, FirstPointIsTheCurveStartAndLastIsTheCurveEndExactly) {
  const core::Spline s = varying_curvature();
  for (const core::StepSettings& st : {stepping::adaptive(5), stepping::adaptive(1000)}) {
    const stepping::Run r = stepping::run(s, st);
    ASSERT_GE(r.points.size(), 2u);
    EXPECT_EQ(r.points.front().p.x_um, 0);
    EXPECT_EQ(r.points.front().p.y_um, 0);
    EXPECT_EQ(r.points.back().p.x_um, 0);
    EXPECT_EQ(r.points.back().p.y_um, 60000);
  }
}

TEST(CurveWalker, PointsLieOnTheReferenceCurve) {
  const core::Spline s = varying_curvature();
  const stepping::Run r = stepping::run(s, stepping::adaptive(5));
  double worst = 0;
  for (const stepping::Emitted& e : r.points) {
    const Eigen::Vector2d want = reference::span_point(s, e.span, e.t);
    worst = std::max(worst, (stepping::vec(e.p) - want).norm());
  }
  EXPECT_LE(worst, 0.75);  // rounding to whole micrometres on both axes
}

TEST(CurveWalker, AdaptiveChordErrorStaysWithinFiveMicrometresOnRandomCurves) {
  std::mt19937 rng(21);
  testcurves::RandomOptions o = testcurves::default_options();
  o.coord_limit_um = 150000;
  double worst = 0;
  for (int i = 0; i < 25; ++i) {
    const core::Spline s = testcurves::random_spline(rng, o);
    const stepping::Run r = stepping::run(s, stepping::adaptive(5));
    ASSERT_EQ(r.end_error, GeometryError::kOk);
    worst = std::max(worst, stepping::max_chord_error_um(s, r, 24));
  }
  EXPECT_LE(worst, 5.0 + 0.75);  // + rounding of the emitted points to 1 um
}

TEST(CurveWalker, AdaptiveChordErrorStaysWithinToleranceOnRationalCurves) {
  std::mt19937 rng(22);
  testcurves::RandomOptions o = testcurves::default_options();
  o.coord_limit_um = 150000;
  o.rational = true;
  double worst = 0;
  for (int i = 0; i < 30; ++i) {
    const core::Spline s = testcurves::random_spline(rng, o);
    const stepping::Run r = stepping::run(s, stepping::adaptive(20));
    ASSERT_EQ(r.end_error, GeometryError::kOk);
    worst = std::max(worst, stepping::max_chord_error_um(s, r, 24));
  }
  EXPECT_LE(worst, 20.0 + 0.75);
}

TEST(CurveWalker, AdaptiveNeedsFewerPointsThanTheCoarsestSufficientUniformStep) {
  const core::Spline s = varying_curvature();
  const double tol_um = 5.0;
  const stepping::Run adaptive = stepping::run(s, stepping::adaptive(5));
  ASSERT_LE(stepping::max_chord_error_um(s, adaptive), tol_um + 0.75);
  // Coarsest uniform step meeting the same tolerance (measured, not estimated).
  size_t uniform_points = 0;
  for (int n = 1; n <= 2000; n = n < 20 ? n + 1 : n * 11 / 10) {
    const stepping::Run u = stepping::uniform_reference(s, n);
    if (stepping::max_chord_error_um(s, u) <= tol_um + 0.75) {
      uniform_points = u.points.size();
      break;
    }
  }
  ASSERT_GT(uniform_points, 0u);
  EXPECT_LT(adaptive.points.size() * 2, uniform_points)
      << "adaptive " << adaptive.points.size() << " vs uniform " << uniform_points;
}

TEST(CurveWalker, StraightLineNeedsOnlyItsEnds) {
  const core::Spline s = testcurves::clamped_uniform(1, {{0, 0}, {100000, 50000}});
  const stepping::Run r = stepping::run(s, stepping::adaptive(5));
  EXPECT_EQ(r.points.size(), 2u);
}

TEST(CurveWalker, RepeatedInteriorKnotsAndZeroLengthSpansAreSkipped) {
  core::Spline s =
      testcurves::clamped_uniform(2, {{0, 0}, {10000, 0}, {10000, 10000}, {0, 10000}, {0, 20000}});
  // knots 0 0 0 1000 2000 3000 3000 3000 -> make 1000 a double knot (a corner).
  s.knot[4] = s.knot[3];
  const stepping::Run r = stepping::run(s, stepping::adaptive(5));
  EXPECT_EQ(r.end_error, GeometryError::kOk);
  bool on_span[8] = {};  // the two non-empty spans are 2 and 4
  for (const stepping::Emitted& e : r.points) on_span[e.span] = true;
  EXPECT_TRUE(on_span[2]);
  EXPECT_FALSE(on_span[3]);
  EXPECT_TRUE(on_span[4]);
  EXPECT_EQ(r.points.back().p.y_um, 20000);
}

TEST(CurveWalker, KnotOfMultiplicityDegreePlusOneEmitsBothSidesOfTheGap) {
  // Quadratic, interior knot 1000 three times: the curve jumps from (20000, 0) to (30000, 0).
  core::Spline s = testcurves::empty_spline();
  s.degree = 2;
  s.control_count = 6;
  s.knot_count = 9;
  const int32_t knots[9] = {0, 0, 0, 1000, 1000, 1000, 2000, 2000, 2000};
  const int32_t xy[6][2] = {{0, 0},     {10000, 10000}, {20000, 0},
                            {30000, 0}, {40000, 10000}, {50000, 0}};
  for (int i = 0; i < 9; ++i) s.knot[i] = knots[i];
  for (int i = 0; i < 6; ++i) {
    s.control[i].x_um = xy[i][0];
    s.control[i].y_um = xy[i][1];
    s.control[i].weight_q14 = core::kWeightOneQ14;
  }
  const stepping::Run r = stepping::run(s, stepping::adaptive(5));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  int gap = -1;  // the joint gives two points: the end of one side, the start of the other
  for (size_t i = 1; i < r.points.size(); ++i) {
    const core::PointUm a = r.points[i - 1].p;
    const core::PointUm b = r.points[i].p;
    if (a.x_um == 20000 && a.y_um == 0 && b.x_um == 30000 && b.y_um == 0) gap = (int)i;
  }
  EXPECT_GT(gap, 0);
  EXPECT_EQ(r.points.back().p.x_um, 50000);
}

TEST(CurveWalker, BadSettingsAndBadSplinesAreRefusedWithACode) {
  const core::Spline good = varying_curvature();
  core::CurveWalker st;
  core::PointUm p;
  core::StepSettings unknown_mode = stepping::adaptive(5);
  unknown_mode.mode = static_cast<core::StepMode>(0);  // the former uniform mode
  EXPECT_EQ(st.begin(&good, unknown_mode), GeometryError::kToleranceInvalid);
  EXPECT_FALSE(st.next(&p));
  EXPECT_EQ(st.begin(&good, stepping::adaptive(0)), GeometryError::kToleranceInvalid);
  EXPECT_FALSE(st.next(&p));
  EXPECT_EQ(st.begin(&good, stepping::adaptive(5, core::kMaxToolOffsetUm + 1)),
            GeometryError::kOffsetTooLarge);
  core::Spline bad = good;
  bad.knot[5] = bad.knot[4] - 1;
  EXPECT_EQ(st.begin(&bad, stepping::adaptive(5)), GeometryError::kKnotsDecreasing);
  EXPECT_FALSE(st.next(&p));
  EXPECT_TRUE(st.done());
}

TEST(CurveWalker, TerminatesOnPathologicalKnotsWithBoundedPointCounts) {
  std::mt19937 rng(23);
  testcurves::RandomOptions o = testcurves::default_options();
  o.knot_lo = INT32_MIN;
  o.knot_hi = INT32_MAX;
  for (int i = 0; i < 30; ++i) {
    const core::Spline s = testcurves::random_spline(rng, o);
    const stepping::Run r = stepping::run(s, stepping::adaptive(1), 2000000);
    EXPECT_EQ(r.end_error, GeometryError::kOk);
    EXPECT_LT(r.points.size(), 2000000u);
  }
}

}  // namespace
