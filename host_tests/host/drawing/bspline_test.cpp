// B-spline operations: evaluation against Eigen, reversal, knot insertion, clamping and
// Bezier decomposition keep the shape; sampling honours its tolerance; extents are tight.
#include "host/lib/drawing/bspline.h"

#include <gtest/gtest.h>

#include <cmath>  // std::sqrt, std::sin, std::cos

#include "host_tests/host/drawing/eigen_reference.h"

namespace host {
namespace {

// An unclamped rational cubic with a negative knot range.
BSpline unclamped_rational_cubic() {
  BSpline s;
  s.degree = 3;
  s.control = {{0, 0}, {10, 20}, {30, 25}, {40, 0}, {55, -10}, {70, 5}};
  s.weights = {1.0, 0.5, 2.0, 1.0, 0.8, 1.0};
  s.knots = {-7, -6, -5, -4, -2.5, -1, 0, 1, 2, 3};
  return s;
}

// Largest distance between a and b over n parameters spread over each's range.
double max_gap(const BSpline& a, const BSpline& b, bool b_reversed = false) {
  double worst = 0;
  const int n = 200;
  for (int i = 0; i <= n; ++i) {
    const double f = static_cast<double>(i) / n;
    const double ta = a.t_min() + (a.t_max() - a.t_min()) * f;
    const double tb = b_reversed ? b.t_max() - (b.t_max() - b.t_min()) * f
                                 : b.t_min() + (b.t_max() - b.t_min()) * f;
    worst = std::max(worst, (evaluate(a, ta) - evaluate(b, tb)).norm());
  }
  return worst;
}

TEST(BSpline, EvaluateMatchesEigenOnUnclampedRationalCubic) {
  const BSpline s = unclamped_rational_cubic();
  for (int i = 0; i <= 100; ++i) {
    const double t = s.t_min() + (s.t_max() - s.t_min()) * i / 100.0;
    EXPECT_LT((evaluate(s, t) - test::eigen_point(s, t)).norm(), 1e-9) << "t=" << t;
  }
}

TEST(BSpline, CheckAcceptsAWellFormedSpline) {
  EXPECT_EQ(check_bspline(unclamped_rational_cubic()), "");
}

TEST(BSpline, CheckNamesDecreasingKnots) {
  BSpline s = unclamped_rational_cubic();
  s.knots[5] = -3;
  EXPECT_NE(check_bspline(s).find("knots decrease at index 5"), std::string::npos);
}

TEST(BSpline, CheckNamesZeroWeight) {
  BSpline s = unclamped_rational_cubic();
  s.weights[2] = 0;
  EXPECT_NE(check_bspline(s).find("weight 2 is 0"), std::string::npos);
}

TEST(BSpline, CheckNamesKnotCountMismatch) {
  BSpline s = unclamped_rational_cubic();
  s.knots.pop_back();
  EXPECT_NE(check_bspline(s).find("9 knots for 6 control points of degree 3 (need 10)"),
            std::string::npos);
}

TEST(BSpline, ReversedTracesTheSameCurveBackwards) {
  const BSpline s = unclamped_rational_cubic();
  const BSpline r = reversed(s);
  EXPECT_LT((start_point(r) - end_point(s)).norm(), 1e-12);
  EXPECT_LT(max_gap(s, r, true), 1e-9);
}

TEST(BSpline, KnotInsertionKeepsTheShape) {
  const BSpline s = unclamped_rational_cubic();
  const BSpline r = insert_knot(s, -1.7);
  EXPECT_EQ(r.control.size(), s.control.size() + 1);
  EXPECT_LT(max_gap(s, r), 1e-9);
}

TEST(BSpline, ClampedKeepsTheShapeAndStartsAtTheFirstControlPoint) {
  const BSpline s = unclamped_rational_cubic();
  const BSpline c = clamped(s);
  EXPECT_EQ(check_bspline(c), "");
  EXPECT_LT(max_gap(s, c), 1e-9);
  EXPECT_LT((c.control.front() - start_point(s)).norm(), 1e-9);
  EXPECT_LT((c.control.back() - end_point(s)).norm(), 1e-9);
}

TEST(BSpline, BezierPiecesOnePerSpanJoinUpToTheCurve) {
  const BSpline s = unclamped_rational_cubic();
  const std::vector<BSpline> pieces = bezier_pieces(s);
  ASSERT_EQ(pieces.size(), 3u);  // spans [-4,-2.5], [-2.5,-1], [-1,0]
  for (const BSpline& p : pieces) {
    EXPECT_EQ(p.control.size(), 4u);
    for (int i = 0; i <= 20; ++i) {
      const double t = p.t_min() + (p.t_max() - p.t_min()) * i / 20.0;
      EXPECT_LT((evaluate(p, t) - evaluate(s, t)).norm(), 1e-9);
    }
  }
}

TEST(BSpline, SampleChordsStayWithinTolerance) {
  const BSpline s = unclamped_rational_cubic();
  const double tol = 0.01;
  const std::vector<Point2> pts = sample(s, tol);
  // Every curve point lies within tol of the polyline (dense check).
  for (int i = 0; i <= 2000; ++i) {
    const Point2 q = evaluate(s, s.t_min() + (s.t_max() - s.t_min()) * i / 2000.0);
    double best = 1e300;
    for (size_t k = 1; k < pts.size(); ++k) {
      const Point2 d = pts[k] - pts[k - 1];
      const double u = std::clamp((q - pts[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (pts[k - 1] + u * d - q).norm());
    }
    EXPECT_LE(best, tol * 1.01);
  }
}

// A wave whose every piece's middle lies on its chord, its quarter points 1 mm off it
// (y vanishes at each eighth of the span, sample's pieces are quarters): the quarter
// points are checked too, so it is sampled within the tolerance.
TEST(BSpline, SampleChecksAPiecesQuarterPointsNotOnlyItsMiddle) {
  const int n = 9;  // y(t) = c * prod_{k=0..8} (t - k/8), x(t) = t: one Bezier span
  std::vector<double> power(n + 1, 0.0);
  power[0] = 1;
  for (int k = 0; k <= 8; ++k) {  // multiply by (t - k/8)
    for (int j = n; j >= 0; --j) power[j] = (j > 0 ? power[j - 1] : 0) - k / 8.0 * power[j];
  }
  auto binom = [](int a, int b) {
    double r = 1;
    for (int i = 1; i <= b; ++i) r = r * (a - b + i) / i;
    return r;
  };
  BSpline s;
  s.degree = n;
  for (int i = 0; i <= n; ++i) {
    double y = 0;  // Bernstein coefficient from the power basis
    for (int j = 0; j <= i; ++j) y += binom(i, j) / binom(n, j) * power[j];
    s.control.push_back(Point2(static_cast<double>(i) / n, y));
  }
  s.knots.assign(n + 1, 0.0);
  s.knots.insert(s.knots.end(), n + 1, 1.0);
  const double peak = std::fabs(evaluate(s, 1.0 / 16).y());
  for (Point2& c : s.control) c.y() /= peak;  // 1 mm at the first quarter point
  ASSERT_NEAR(evaluate(s, 1.0 / 8).y(), 0.0, 1e-12);
  ASSERT_NEAR(std::fabs(evaluate(s, 1.0 / 16).y()), 1.0, 1e-9);
  const double tol = 0.01;
  const std::vector<Point2> pts = sample(s, tol);
  for (int i = 0; i <= 2000; ++i) {
    const Point2 q = evaluate(s, i / 2000.0);
    double best = 1e300;
    for (size_t k = 1; k < pts.size(); ++k) {
      const Point2 d = pts[k] - pts[k - 1];
      const double u = std::clamp((q - pts[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (pts[k - 1] + u * d - q).norm());
    }
    EXPECT_LE(best, tol * 1.01) << "at t = " << i / 2000.0;
  }
}

// Extents of 200 001 Eigen-evaluated points: below the true ones by far less than 1 nm on
// these curves (points about 1 um apart, so an extreme is missed by ~(1 um)^2 x curvature).
Extents dense_reference_extents(const BSpline& s) {
  Extents e;
  const int n = 200000;
  for (int i = 0; i <= n; ++i)
    e.add(test::eigen_point(s, s.t_min() + (s.t_max() - s.t_min()) * i / n));
  return e;
}

void expect_same_extents(const Extents& got, const Extents& want) {
  EXPECT_NEAR(got.min.x(), want.min.x(), 2e-6);
  EXPECT_NEAR(got.min.y(), want.min.y(), 2e-6);
  EXPECT_NEAR(got.max.x(), want.max.x(), 2e-6);
  EXPECT_NEAR(got.max.y(), want.max.y(), 2e-6);
}

TEST(BSpline, ExtentsOfAnUnclampedRationalCubicMatchDenseEigenPoints) {
  const BSpline s = unclamped_rational_cubic();
  expect_same_extents(curve_extents(s), dense_reference_extents(s));
}

TEST(BSpline, ExtentsOfARationalCircleAreItsBoundingSquare) {
  // The nine-point NURBS circle of radius 5 about (3, 4).
  BSpline c;
  c.degree = 2;
  const double r = 5.0;
  const double w = std::sqrt(0.5);
  c.control = {{8, 4}, {8, 9}, {3, 9}, {-2, 9}, {-2, 4}, {-2, -1}, {3, -1}, {8, -1}, {8, 4}};
  c.weights = {1, w, 1, w, 1, w, 1, w, 1};
  c.knots = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
  ASSERT_EQ(check_bspline(c), "");
  const Extents e = curve_extents(c);
  EXPECT_NEAR(e.min.x(), 3 - r, 1e-6);
  EXPECT_NEAR(e.max.x(), 3 + r, 1e-6);
  EXPECT_NEAR(e.min.y(), 4 - r, 1e-6);
  EXPECT_NEAR(e.max.y(), 4 + r, 1e-6);
}

TEST(BSpline, ExtentsOfAWigglyCubicWithManySpansMatchDenseEigenPoints) {
  // 40 control points on a wave whose peaks fall between control points, unclamped.
  BSpline s;
  s.degree = 3;
  for (int i = 0; i < 40; ++i)
    s.control.push_back(Point2(0.5 * i, 20.0 * std::sin(0.37 * i) + 0.01 * i * std::cos(1.3 * i)));
  for (int i = 0; i < 44; ++i) s.knots.push_back(0.1 * i + 0.003 * (i % 7));
  ASSERT_EQ(check_bspline(s), "");
  expect_same_extents(curve_extents(s), dense_reference_extents(s));
}

}  // namespace
}  // namespace host
