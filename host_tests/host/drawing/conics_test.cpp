// Exact conics: arcs, circles, ellipses and bulge polylines as rational quadratics.
#include "host/lib/drawing/conics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace host {
namespace {

const double kPi = 3.14159265358979323846;

// Largest |distance from centre - radius| over a dense parameter sweep.
double radius_error(const BSpline& s, const Point2& c, double r) {
  double worst = 0;
  for (int i = 0; i <= 1000; ++i) {
    const double t = s.t_min() + (s.t_max() - s.t_min()) * i / 1000.0;
    worst = std::max(worst, std::fabs((evaluate(s, t) - c).norm() - r));
  }
  return worst;
}

TEST(Conics, LineIsDegreeOneThroughItsEnds) {
  const BSpline s = line_spline({1, 2}, {4, 6});
  EXPECT_EQ(s.degree, 1);
  EXPECT_LT((evaluate(s, 0.5) - Point2(2.5, 4)).norm(), 1e-12);
}

TEST(Conics, FullCircleIsFourExactQuarterPieces) {
  const BSpline s = arc_spline({10, 20}, 5.0, 0.0, 2 * kPi);
  EXPECT_EQ(s.degree, 2);
  EXPECT_EQ(s.control.size(), 9u);  // 4 pieces of <= 90 degrees
  EXPECT_NEAR(s.weights[1], std::cos(kPi / 4), 1e-15);
  EXPECT_LT(radius_error(s, {10, 20}, 5.0), 1e-12);
  EXPECT_LT((start_point(s) - end_point(s)).norm(), 1e-12);
}

TEST(Conics, ClockwiseArcCrossingZeroDegreesStaysOnTheCircle) {
  const BSpline s = arc_spline({0, 0}, 3.0, 30 * kPi / 180, -100 * kPi / 180);
  EXPECT_EQ(s.control.size(), 5u);  // 100 degrees: 2 pieces
  EXPECT_LT(radius_error(s, {0, 0}, 3.0), 1e-12);
  EXPECT_LT(
      (end_point(s) - 3.0 * Point2(std::cos(-70 * kPi / 180), std::sin(-70 * kPi / 180))).norm(),
      1e-12);
}

TEST(Conics, EllipseArcSatisfiesTheEllipseEquation) {
  // Major axis along 30 degrees, length 8; ratio 0.5.
  const Point2 major = 8.0 * Point2(std::cos(kPi / 6), std::sin(kPi / 6));
  const Point2 minor = 0.5 * Point2(-major.y(), major.x());
  const BSpline s = ellipse_spline({1, 1}, major, minor, 0.3, 4.0);
  for (int i = 0; i <= 500; ++i) {
    const Point2 p = evaluate(s, s.t_min() + (s.t_max() - s.t_min()) * i / 500.0) - Point2(1, 1);
    const double u = p.dot(major) / major.squaredNorm();
    const double v = p.dot(minor) / minor.squaredNorm();
    EXPECT_NEAR(u * u + v * v, 1.0, 1e-12);
  }
  EXPECT_LT(
      (start_point(s) - (Point2(1, 1) + std::cos(0.3) * major + std::sin(0.3) * minor)).norm(),
      1e-12);
}

TEST(Conics, BulgeOneIsACounterClockwiseHalfCircle) {
  std::vector<BulgeVertex> v(2);
  v[0].p = {0, 0};
  v[0].bulge = 1.0;  // tan(180 deg / 4)
  v[1].p = {10, 0};
  const BSpline s = polyline_spline(v, false);
  EXPECT_LT(radius_error(s, {5, 0}, 5.0), 1e-12);
  // Counter-clockwise from (0,0) to (10,0) about (5,0) passes below: (5,-5).
  EXPECT_LT((evaluate(s, 0.5 * (s.t_min() + s.t_max())) - Point2(5, -5)).norm(), 1e-9);
}

TEST(Conics, NegativeBulgeQuarterArcIsClockwise) {
  std::vector<BulgeVertex> v(2);
  v[0].p = {0, 0};
  v[0].bulge = -std::tan(kPi / 8);  // -90 degrees
  v[1].p = {5, 5};
  const BSpline s = polyline_spline(v, false);
  // Clockwise quarter from (0,0) to (5,5): centre (5,0).
  EXPECT_LT(radius_error(s, {5, 0}, 5.0), 1e-12);
}

TEST(Conics, StraightPolylineIsDegreeOneThroughItsVertices) {
  std::vector<BulgeVertex> v(3);
  v[0].p = {0, 0};
  v[1].p = {10, 0};
  v[2].p = {10, 10};
  const BSpline s = polyline_spline(v, true);
  EXPECT_EQ(s.degree, 1);
  EXPECT_EQ(s.control.size(), 4u);  // closed: back to the start
  EXPECT_LT((end_point(s) - Point2(0, 0)).norm(), 1e-15);
}

TEST(Conics, PolylineMixingLinesAndBulgesJoinsExactly) {
  std::vector<BulgeVertex> v(3);
  v[0].p = {0, 0};
  v[1].p = {10, 0};
  v[1].bulge = std::tan(kPi / 8);
  v[2].p = {15, 5};
  const BSpline s = polyline_spline(v, false);
  EXPECT_EQ(s.degree, 2);
  EXPECT_EQ(s.control.size(), 5u);  // line raised to degree 2 + one quarter arc
  EXPECT_LT((evaluate(s, 1.0) - Point2(10, 0)).norm(), 1e-15);
  EXPECT_LT((end_point(s) - Point2(15, 5)).norm(), 1e-15);
}

TEST(Conics, PolylineOfOneVertexHasNothingToDraw) {
  std::vector<BulgeVertex> v(1);
  EXPECT_TRUE(polyline_spline(v, false).control.empty());
}

}  // namespace
}  // namespace host
