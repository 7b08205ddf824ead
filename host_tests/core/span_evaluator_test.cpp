// SpanEvaluator against the Eigen double reference: random and pathological curves,
// polynomial and rational; the figure that matters is the max error in micrometres.
#include "firmware/core/span_evaluator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "host_tests/core/curve_factory.h"
#include "host_tests/core/spline_reference.h"

namespace {

// Largest distance (um) between the evaluator and Eigen over every span of s, at
// samples_per_span parameters per span (t = 0, spread values, and the end t = 1).
double max_error_um(const core::Spline& s, int samples_per_span, std::mt19937& rng) {
  const reference::Curve curve(s);
  double worst = 0;
  for (uint16_t span = core::first_span(s); span < core::span_end(s);
       span = core::next_span(s, span)) {
    core::SpanEvaluator e;
    EXPECT_EQ(e.setup(s, span), core::GeometryError::kOk);
    for (int k = 0; k <= samples_per_span; ++k) {
      uint32_t t_q16 = (uint32_t)((uint64_t)k * 65536 / samples_per_span);
      if (k > 0 && k < samples_per_span) t_q16 = rng() % 65536;
      const core::PointQ6 got = e.evaluate_q6(t_q16);
      const Eigen::Vector2d want = curve.at_span(span, t_q16 / 65536.0);
      const double err = std::hypot(got.x_q6 / 64.0 - want.x(), got.y_q6 / 64.0 - want.y());
      worst = std::max(worst, err);
    }
  }
  return worst;
}

TEST(SpanEvaluator, RandomPolynomialCurvesWithinHalfMicrometreOfEigen) {
  std::mt19937 rng(1);
  const testcurves::RandomOptions o = testcurves::default_options();
  double worst = 0;
  for (int i = 0; i < 300; ++i)
    worst = std::max(worst, max_error_um(testcurves::random_spline(rng, o), 8, rng));
  EXPECT_LE(worst, 0.5);
}

TEST(SpanEvaluator, RandomRationalCurvesWithinHalfMicrometreOfEigen) {
  std::mt19937 rng(2);
  testcurves::RandomOptions o = testcurves::default_options();
  o.rational = true;
  o.weight_min_q14 = 4096;   // 0.25
  o.weight_max_q14 = 65535;  // 4 - 2^-14
  double worst = 0;
  for (int i = 0; i < 300; ++i)
    worst = std::max(worst, max_error_um(testcurves::random_spline(rng, o), 8, rng));
  EXPECT_LE(worst, 0.5);
}

TEST(SpanEvaluator, HugeAndNegativeKnotRangesWithinHalfMicrometre) {
  std::mt19937 rng(3);
  testcurves::RandomOptions o = testcurves::default_options();
  o.knot_lo = INT32_MIN;
  o.knot_hi = INT32_MAX;
  double worst = 0;
  for (int i = 0; i < 200; ++i)
    worst = std::max(worst, max_error_um(testcurves::random_spline(rng, o), 8, rng));
  EXPECT_LE(worst, 0.5);
}

TEST(SpanEvaluator, TinySpanBetweenHugeSpansWithinHalfMicrometre) {
  // Knot differences 1 next to 2^31: the normalisation must keep full precision.
  core::Spline s = testcurves::empty_spline();
  s.degree = 3;
  s.control_count = 6;
  s.knot_count = 10;
  const int32_t knots[10] = {INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN, 0,
                             1,         INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX};
  const int32_t xy[6][2] = {{-1000000, -1000000}, {1000000, -1000000}, {1000000, 1000000},
                            {-1000000, 1000000},  {-1000000, -999999}, {1000000, 0}};
  for (int i = 0; i < 10; ++i) s.knot[i] = knots[i];
  for (int i = 0; i < 6; ++i) {
    s.control[i].x_um = xy[i][0];
    s.control[i].y_um = xy[i][1];
    s.control[i].weight_q14 = core::kWeightOneQ14;
  }
  ASSERT_EQ(core::validate_spline(s), core::GeometryError::kOk);
  std::mt19937 rng(4);
  EXPECT_LE(max_error_um(s, 64, rng), 0.5);
  s.rational = true;
  s.control[2].weight_q14 = 65535;
  s.control[3].weight_q14 = 4096;
  EXPECT_LE(max_error_um(s, 64, rng), 0.5);
}

TEST(SpanEvaluator, ControlPointsAtTheCoordinateLimitsWithinHalfMicrometre) {
  std::mt19937 rng(5);
  double worst = 0;
  for (int i = 0; i < 100; ++i) {
    testcurves::RandomOptions o = testcurves::default_options();
    core::Spline s = testcurves::random_spline(rng, o);
    for (int c = 0; c < s.control_count; ++c) {  // every point on a corner of the range
      s.control[c].x_um = (rng() % 2) ? core::kMaxCoordinateUm : -core::kMaxCoordinateUm;
      s.control[c].y_um = (rng() % 2) ? core::kMaxCoordinateUm : -core::kMaxCoordinateUm;
    }
    worst = std::max(worst, max_error_um(s, 8, rng));
  }
  EXPECT_LE(worst, 0.5);
}

TEST(SpanEvaluator, ExtremeWeightRatioStaysWithinDocumentedBound) {
  // Weights 2^-14 next to 4 - 2^-14 (ratio 65535): 0.5 um is not met there; core-math.md
  // documents the bound (measured 2.0 um over 2000 curves at +-1 m), asserted as 4 um.
  std::mt19937 rng(6);
  testcurves::RandomOptions o = testcurves::default_options();
  o.rational = true;
  o.weight_min_q14 = 1;
  o.weight_max_q14 = 65535;
  double worst = 0;
  for (int i = 0; i < 200; ++i)
    worst = std::max(worst, max_error_um(testcurves::random_spline(rng, o), 8, rng));
  EXPECT_LE(worst, 4.0);
}

TEST(SpanEvaluator, ExactCircleStaysOnItsRadius) {
  const core::Spline s = testcurves::circle(1000, -2000, 50000);
  double worst = 0;
  for (uint16_t span = core::first_span(s); span < core::span_end(s);
       span = core::next_span(s, span)) {
    core::SpanEvaluator e;
    ASSERT_EQ(e.setup(s, span), core::GeometryError::kOk);
    for (uint32_t t = 0; t <= 65536; t += 512) {
      const core::PointQ6 p = e.evaluate_q6(t);
      const double r = std::hypot(p.x_q6 / 64.0 - 1000, p.y_q6 / 64.0 + 2000);
      worst = std::max(worst, std::fabs(r - 50000));
    }
  }
  EXPECT_LE(worst, 0.5);  // weights are rounded to Q14: the radius error stays small
}

TEST(SpanEvaluator, SpanEndEqualsNextSpanStartAndClampedEndsHitControlPoints) {
  std::mt19937 rng(7);
  const core::Spline s = testcurves::clamped_uniform(
      3, {{0, 0}, {10000, 5000}, {20000, -5000}, {30000, 7000}, {40000, 0}, {-5000, 123}});
  core::SpanEvaluator a, b;
  uint16_t span = core::first_span(s);
  ASSERT_EQ(a.setup(s, span), core::GeometryError::kOk);
  EXPECT_EQ(a.start_point().x_um, 0);
  EXPECT_EQ(a.start_point().y_um, 0);
  for (uint16_t nx = core::next_span(s, span); nx < core::span_end(s);
       nx = core::next_span(s, nx)) {
    ASSERT_EQ(b.setup(s, nx), core::GeometryError::kOk);
    EXPECT_LE(std::abs(a.end_point().x_um - b.start_point().x_um), 1);
    EXPECT_LE(std::abs(a.end_point().y_um - b.start_point().y_um), 1);
    a = b;
  }
  EXPECT_EQ(a.end_point().x_um, -5000);
  EXPECT_EQ(a.end_point().y_um, 123);
}

// step_bend_q6 against Eigen: with f(s) = P(t0 + h s) a cubic in s, the third difference
// f(1) - 3 f(2/3) + 3 f(1/3) - f(0) is 2 a3 / 9 and f(0) - 2 f(1/2) + f(1) is
// a2 / 2 + 3 a3 / 4, exactly.
TEST(SpanEvaluator, StepBendIsTheTaylorCoefficientsOfTheStep) {
  std::mt19937 rng(7);
  const testcurves::RandomOptions o = testcurves::default_options();
  double worst_um = 0;
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const core::Spline s = testcurves::random_spline(rng, o);
    const reference::Curve curve(s);
    for (uint16_t span = core::first_span(s); span < core::span_end(s);
         span = core::next_span(s, span)) {
      core::SpanEvaluator e;
      ASSERT_EQ(e.setup(s, span), core::GeometryError::kOk);
      const uint32_t t0 = rng() % 65536;
      uint32_t h = 1 + rng() % (65536 - t0);
      if (i % 4 == 0) h = 65536 - t0;  // up to the span end (t0 0 and h 1 included)
      core::PointQ6 a2;
      core::PointQ6 a3;
      // Spans whose coefficients are too large (the random extremes) are refused.
      if (!e.step_bend_q6(t0, h, &a2, &a3)) continue;
      auto f = [&](double frac) { return curve.at_span(span, (t0 + h * frac) / 65536.0); };
      const Eigen::Vector2d want3 = (f(1) - 3 * f(2.0 / 3) + 3 * f(1.0 / 3) - f(0)) * 4.5;
      const Eigen::Vector2d want2 = (f(0) - 2 * f(0.5) + f(1) - 0.75 * want3) * 2;
      const Eigen::Vector2d got2(a2.x_q6 / 64.0, a2.y_q6 / 64.0);
      const Eigen::Vector2d got3(a3.x_q6 / 64.0, a3.y_q6 / 64.0);
      worst_um = std::max(worst_um, std::max((got2 - want2).norm(), (got3 - want3).norm()));
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
  EXPECT_LE(worst_um, 0.5);
}

TEST(SpanEvaluator, StepBendIsRefusedOnRationalSpans) {
  std::mt19937 rng(8);
  testcurves::RandomOptions o = testcurves::default_options();
  o.rational = true;
  const core::Spline s = testcurves::random_spline(rng, o);
  core::SpanEvaluator e;
  ASSERT_EQ(e.setup(s, core::first_span(s)), core::GeometryError::kOk);
  core::PointQ6 a2;
  core::PointQ6 a3;
  EXPECT_FALSE(e.step_bend_q6(0, 4096, &a2, &a3));
}

TEST(SpanEvaluator, RefusesAZeroLengthOrOutOfDomainSpan) {
  const core::Spline s = testcurves::clamped_uniform(2, {{0, 0}, {1, 1}, {2, 0}, {3, 3}});
  core::SpanEvaluator e;
  EXPECT_EQ(e.setup(s, 0), core::GeometryError::kKnotRangeEmpty);  // before the domain
  EXPECT_EQ(e.setup(s, 1), core::GeometryError::kKnotRangeEmpty);  // zero length
  EXPECT_EQ(e.setup(s, 4), core::GeometryError::kKnotRangeEmpty);  // past the end
  EXPECT_EQ(e.setup(s, 2), core::GeometryError::kOk);
}

TEST(SpanEvaluator, UnvalidatedBadWindowIsRefusedNotEvaluated) {
  core::Spline s = testcurves::clamped_uniform(2, {{0, 0}, {1000, 1000}, {2000, 0}, {3000, 3000}});
  core::SpanEvaluator e;
  core::Spline bad = s;
  bad.knot[1] = 500;  // 0 500 0 ...: decreasing inside span 2's window
  EXPECT_EQ(e.setup(bad, 2), core::GeometryError::kKnotsDecreasing);
  bad = s;
  bad.rational = true;
  bad.control[1].weight_q14 = 0;
  EXPECT_EQ(e.setup(bad, 2), core::GeometryError::kZeroWeight);
  bad = s;
  bad.control[0].x_um = core::kMaxCoordinateUm + 1;
  EXPECT_EQ(e.setup(bad, 2), core::GeometryError::kCoordinateOutOfRange);
  bad = s;
  bad.control_count = 200;  // would read past the arrays
  EXPECT_EQ(e.setup(bad, 150), core::GeometryError::kKnotRangeEmpty);
}

}  // namespace
