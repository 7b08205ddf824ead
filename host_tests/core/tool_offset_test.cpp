// Tool-radius offset in CurveWalker: exact circles offset to r -/+ R, corner arcs and
// miters on polygons, and kOffsetTooLarge when R exceeds the radius of curvature.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/core/curve_walker.h"
#include "host_tests/core/curve_factory.h"
#include "host_tests/core/curve_walker_helpers.h"

namespace {

using core::GeometryError;

// Largest |distance from (cx, cy) - radius| over the emitted points.
double radius_error_um(const stepping::Run& r, double cx, double cy, double radius) {
  double worst = 0;
  for (const stepping::Emitted& e : r.points)
    worst = std::max(worst, std::fabs(std::hypot(e.p.x_um - cx, e.p.y_um - cy) - radius));
  return worst;
}

// Counter-clockwise square 0..10 mm as a degree-1 spline (4 corners, closed).
core::Spline square_ccw() {
  return testcurves::clamped_uniform(1, {{0, 0}, {10000, 0}, {10000, 10000}, {0, 10000}, {0, 0}});
}

TEST(ToolOffset, LeftOffsetOfACounterClockwiseCircleHasRadiusRMinusOffset) {
  // Travel is counter-clockwise, so left is toward the centre: 20 mm - 1.5 mm.
  const core::Spline s = testcurves::circle(5000, -3000, 20000, true);
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, 1500));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  ASSERT_GT(r.points.size(), 10u);
  EXPECT_LE(radius_error_um(r, 5000, -3000, 18500), 1.0);
}

TEST(ToolOffset, RightOffsetOfACounterClockwiseCircleHasRadiusRPlusOffset) {
  const core::Spline s = testcurves::circle(5000, -3000, 20000, true);
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, -1500));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  EXPECT_LE(radius_error_um(r, 5000, -3000, 21500), 1.0);
}

TEST(ToolOffset, LeftOffsetOfAClockwiseCircleGoesOutward) {
  const core::Spline s = testcurves::circle(0, 0, 10000, false);
  const stepping::Run o = stepping::run(s, stepping::adaptive(5, 2500));
  ASSERT_EQ(o.end_error, GeometryError::kOk);
  for (size_t i = 1; i < o.points.size(); ++i) {  // smooth joints add no arc points
    EXPECT_FALSE(o.points[i].span == o.points[i - 1].span && o.points[i].t == o.points[i - 1].t)
        << i;
  }
  EXPECT_LE(radius_error_um(o, 0, 0, 12500), 1.0);
}

TEST(ToolOffset, OffsetCircleKeepsTheChordTolerance) {
  // Outside offset: the path is longer than the curve, its chord error must still hold.
  const core::Spline s = testcurves::circle(0, 0, 3000, true);
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, -2000));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  // Chord error of a circle of radius 5000 between consecutive points: r - sqrt(r^2 - c^2/4).
  double worst = 0;
  for (size_t i = 1; i < r.points.size(); ++i) {
    const double c = (stepping::vec(r.points[i].p) - stepping::vec(r.points[i - 1].p)).norm();
    worst = std::max(worst, 5000.0 - std::sqrt(5000.0 * 5000.0 - c * c / 4));
  }
  EXPECT_LE(worst, 5.0 + 0.75);
}

// Smallest radius of curvature on the offset side (left for R > 0), sampled densely.
double min_offset_side_radius_um(const core::Spline& s, int32_t r_um) {
  const reference::Curve curve(s);
  const double lo = s.knot[s.degree], hi = s.knot[s.control_count];
  double best = 1e300;
  for (int k = 0; k <= 20000; ++k) {
    const double kappa = curve.curvature(lo + (hi - lo) * k / 20000.0);
    if (kappa * r_um > 0) best = std::min(best, 1.0 / std::fabs(kappa));
  }
  return best;
}

TEST(ToolOffset, OffsetPointsMatchTheDoubleOffsetOfRandomSmoothCurves) {
  // Smooth cubics (uniform clamped knots: no corners), R = +-300 um: every emitted point is
  // the Eigen curve point plus R times the Eigen unit normal at the same parameter, and a
  // stop (kOffsetTooLarge) happens only on curves that really turn tighter than R.
  std::mt19937 rng(31);
  std::uniform_int_distribution<int32_t> coord(-100000, 100000);
  double worst = 0;
  int finished = 0;
  for (int i = 0; i < 40; ++i) {
    std::vector<std::pair<int32_t, int32_t>> pts(8);
    for (auto& p : pts) p = {coord(rng), coord(rng)};
    const core::Spline s = testcurves::clamped_uniform(3, pts);
    const int32_t r_um = (i % 2) ? 300 : -300;
    const stepping::Run r = stepping::run(s, stepping::adaptive(5, r_um));
    if (r.end_error == GeometryError::kOk) {
      ++finished;
    } else {
      EXPECT_EQ(r.end_error, GeometryError::kOffsetTooLarge);
      EXPECT_LT(min_offset_side_radius_um(s, r_um), 300.0) << "curve " << i;
    }
    const reference::Curve curve(s);
    for (const stepping::Emitted& e : r.points) {
      const double u = reference::span_u(s, e.span, e.t);
      const Eigen::Vector2d d = curve.derivative(u).normalized();
      const Eigen::Vector2d want = curve.at(u) + r_um * Eigen::Vector2d(-d.y(), d.x());
      worst = std::max(worst, (stepping::vec(e.p) - want).norm());
    }
  }
  EXPECT_LE(worst, 1.0);
  EXPECT_GE(finished, 15);  // 22 of these 40 random curves have no radius under 0.3 mm
}

TEST(ToolOffset, OffsetLargerThanTheInsideRadiusStopsWithOffsetTooLarge) {
  const core::Spline s = testcurves::circle(0, 0, 5000, true);  // left = inside
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, 6000));
  EXPECT_EQ(r.end_error, GeometryError::kOffsetTooLarge);
  EXPECT_LT(r.points.size(), 4u);  // detected on the first steps
}

TEST(ToolOffset, TheSameOffsetOnTheOutsideIsFine) {
  const core::Spline s = testcurves::circle(0, 0, 5000, true);
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, -6000));
  EXPECT_EQ(r.end_error, GeometryError::kOk);
  EXPECT_LE(radius_error_um(r, 0, 0, 11000), 1.0);
}

TEST(ToolOffset, OffsetJustBelowTheInsideRadiusIsAccepted) {
  const core::Spline s = testcurves::circle(0, 0, 5000, true);
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, 4500));
  EXPECT_EQ(r.end_error, GeometryError::kOk);
  EXPECT_LE(radius_error_um(r, 0, 0, 500), 1.0);
}

TEST(ToolOffset, ConvexCornersAreRoundedOnArcsOfRadiusRAboutTheCorner) {
  // Right offset of a counter-clockwise square is outside: every corner is convex.
  const stepping::Run r = stepping::run(square_ccw(), stepping::adaptive(5, -1000));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  const double corners[3][2] = {{10000, 0}, {10000, 10000}, {0, 10000}};
  for (const auto& c : corners) {
    int on_arc = 0;
    for (const stepping::Emitted& e : r.points) {
      const double d = std::hypot(e.p.x_um - c[0], e.p.y_um - c[1]);
      if (std::fabs(d - 1000) <= 1.0) ++on_arc;
    }
    // 90 degrees at R = 1 mm, 5 um chord: at least 90 / (2 acos(1 - 5/1000) in deg) = 8.
    EXPECT_GE(on_arc, 9) << "corner " << c[0] << "," << c[1];
  }
  // Every point is exactly R from the square (outside it).
  for (const stepping::Emitted& e : r.points) {
    const double dx = std::max(0.0, std::max(-e.p.x_um * 1.0, e.p.x_um - 10000.0));
    const double dy = std::max(0.0, std::max(-e.p.y_um * 1.0, e.p.y_um - 10000.0));
    EXPECT_NEAR(std::hypot(dx, dy), 1000.0, 1.0) << e.p.x_um << "," << e.p.y_um;
  }
}

TEST(ToolOffset, KnotOfMultiplicityDegreeMakesACornerThatIsRoundedOnAnArc) {
  // Quadratic through (0,0) -> corner (10000,0) -> (10000,10000): the double knot 1000
  // (multiplicity = degree) makes the curve pass through the corner control point with a
  // 90-degree tangent break. Right offset of a left turn is the outside: an arc.
  core::Spline s = testcurves::empty_spline();
  s.degree = 2;
  s.control_count = 5;
  s.knot_count = 8;
  const int32_t knots[8] = {0, 0, 0, 1000, 1000, 2000, 2000, 2000};
  const int32_t xy[5][2] = {{0, 0}, {5000, 0}, {10000, 0}, {10000, 5000}, {10000, 10000}};
  for (int i = 0; i < 8; ++i) s.knot[i] = knots[i];
  for (int i = 0; i < 5; ++i) {
    s.control[i].x_um = xy[i][0];
    s.control[i].y_um = xy[i][1];
    s.control[i].weight_q14 = core::kWeightOneQ14;
  }
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, -800));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  int on_arc = 0;
  for (const stepping::Emitted& e : r.points) {
    if (e.p.x_um >= 10000 && e.p.y_um <= 0) {  // the quadrant beyond the corner
      EXPECT_NEAR(std::hypot(e.p.x_um - 10000.0, e.p.y_um), 800.0, 1.0);
      ++on_arc;
    }
  }
  EXPECT_GE(on_arc, 8);  // both ends and arc points in between
  EXPECT_NEAR(r.points.front().p.y_um, -800, 1);
  EXPECT_NEAR(r.points.back().p.x_um, 10800, 1);
}

TEST(ToolOffset, ConcaveCornersGetTheMiterPoint) {
  // Left offset of a counter-clockwise square is inside: corners become miter points.
  const stepping::Run r = stepping::run(square_ccw(), stepping::adaptive(5));
  const stepping::Run o = stepping::run(square_ccw(), stepping::adaptive(5, 1000));
  ASSERT_EQ(o.end_error, GeometryError::kOk);
  ASSERT_EQ(o.points.size(), r.points.size());  // one point per corner, no arcs
  const int expected[5][2] = {{0, 1000}, {9000, 1000}, {9000, 9000}, {1000, 9000}, {1000, 0}};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(o.points[i].p.x_um, expected[i][0], 1) << i;
    EXPECT_NEAR(o.points[i].p.y_um, expected[i][1], 1) << i;
  }
}

TEST(ToolOffset, ConcaveTurnSharperThan150DegreesStopsWithOffsetTooLarge) {
  // A 170-degree hairpin turning left with a left offset.
  const core::Spline s = testcurves::clamped_uniform(1, {{0, 0}, {20000, 0}, {0, 3500}});
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, 500));
  EXPECT_EQ(r.end_error, GeometryError::kOffsetTooLarge);
}

TEST(ToolOffset, ConvexReversalGoesRoundTheEndOnAHalfCircle) {
  // Out and straight back: the right offset turns 180 degrees round the far end.
  const core::Spline s = testcurves::clamped_uniform(1, {{0, 0}, {20000, 0}, {0, 0}});
  const stepping::Run r = stepping::run(s, stepping::adaptive(5, -1000));
  ASSERT_EQ(r.end_error, GeometryError::kOk);
  double max_x = 0;
  int on_arc = 0;
  for (const stepping::Emitted& e : r.points) {
    max_x = std::max<double>(max_x, e.p.x_um);
    if (std::fabs(std::hypot(e.p.x_um - 20000.0, e.p.y_um) - 1000) <= 1.0) ++on_arc;
  }
  EXPECT_NEAR(max_x, 21000, 1);  // the tip of the half circle
  EXPECT_GE(on_arc, 17);
  EXPECT_NEAR(r.points.back().p.y_um, 1000, 1);  // came back on the other side
}

}  // namespace
