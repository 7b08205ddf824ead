// Host B-spline -> firmware core::Spline: same shape (to the micrometre rounding), valid,
// long curves split without changing the shape.
#include "host/lib/plan/firmware_spline.h"

#include <gtest/gtest.h>

#include <algorithm>  // std::max_element
#include <cmath>

#include "host/lib/drawing/conics.h"
#include "host_tests/host/drawing/eigen_reference.h"

namespace host {
namespace {

const double kPi = 3.14159265358979323846;

// Largest distance (mm) from points of the firmware pieces (evaluated by Eigen in double)
// to the original curve: each piece point is compared with the nearest point of a dense
// sampling of the original.
double max_deviation_mm(const BSpline& original, const std::vector<core::Spline>& pieces) {
  const std::vector<Point2> dense = sample(original, 1e-4);
  double worst = 0;
  for (const core::Spline& f : pieces) {
    const BSpline b = from_firmware_spline(f);
    for (int i = 0; i <= 50; ++i) {
      const Point2 p = test::eigen_point(b, b.t_min() + (b.t_max() - b.t_min()) * i / 50.0);
      double best = 1e300;
      for (size_t k = 1; k < dense.size(); ++k) {
        const Point2 d = dense[k] - dense[k - 1];
        const double u = std::clamp((p - dense[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
        best = std::min(best, (dense[k - 1] + u * d - p).norm());
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

TEST(FirmwareSpline, PolynomialCubicConvertsToMicrometresAndStaysNonRational) {
  BSpline s;
  s.degree = 3;
  s.control = {{0, 0}, {10.0004, 20}, {30, 25.0006}, {40, 0}};
  s.knots = {-3, -3, -3, -3, 5, 5, 5, 5};
  const std::vector<core::Spline> f = to_firmware_splines(s);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_FALSE(f[0].rational);
  EXPECT_EQ(f[0].control[1].x_um, 10000);
  EXPECT_EQ(f[0].control[2].y_um, 25001);
  EXPECT_EQ(f[0].knot[0], 0);
  EXPECT_EQ(f[0].knot[7], 1);  // one span between full-multiplicity knots: any length will do
  EXPECT_EQ(core::validate_spline(f[0]), core::GeometryError::kOk);
}

TEST(FirmwareSpline, KnotsAreScaledChainByChainWithoutChangingTheShape) {
  // A rational quadratic: a quarter arc (r 0.25 mm), a corner (double knot), then two
  // pieces joined by a single knot whose span ratio (1 : 3) shapes the curve.
  BSpline s;
  s.degree = 2;
  const double c = std::cos(kPi / 4);
  s.control = {{0.25, 0}, {0.25, 0.25}, {0, 0.25}, {-1, 0.5}, {-2, 0.25}, {-3, 1}};
  s.weights = {1, c, 1, 0.8, 1.3, 1};
  s.knots = {0, 0, 0, 0.4, 0.4, 1.1, 3.2, 3.2, 3.2};
  const std::vector<core::Spline> f = to_firmware_splines(s);
  ASSERT_EQ(f.size(), 1u);
  const int32_t* k = f[0].knot;
  EXPECT_EQ(k[3] - k[2], 1);  // the arc: a chain of one span
  EXPECT_EQ(k[4], k[3]);
  const double ratio = static_cast<double>(k[6] - k[5]) / (k[5] - k[4]);
  EXPECT_NEAR(ratio, 3.0, 3e-4);
  // Small units: each span of the chain a few times its control legs in um, far below 2^28.
  EXPECT_LT(k[6] - k[4], 100000);
  EXPECT_GT(k[5] - k[4], 4 * 1000);
  EXPECT_LT(max_deviation_mm(s, f), 0.0003);
}

TEST(FirmwareSpline, DegreeOneKnotsBecomeUniform) {
  BSpline s;
  s.degree = 1;
  s.control = {{0, 0}, {1, 0}, {1, 7}, {3, 7}};
  s.knots = {0, 0, 1, 8, 10, 10};
  const std::vector<core::Spline> f = to_firmware_splines(s);
  ASSERT_EQ(f.size(), 1u);
  const int32_t want[6] = {0, 0, 1, 2, 3, 3};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(f[0].knot[i], want[i]) << i;
}

TEST(FirmwareSpline, SmallArcWeightsUseACoarseGridWithinATenthOfAMicrometre) {
  // A PCB-sized round join: r 0.3 mm; its weights need no more than 1e-4 of precision.
  const BSpline arc = arc_spline({10, 10}, 0.3, 0, kPi);
  const std::vector<core::Spline> f = to_firmware_splines(arc);
  ASSERT_EQ(f.size(), 1u);
  uint16_t largest = 0;
  for (int i = 0; i < f[0].control_count; ++i)
    largest = std::max(largest, f[0].control[i].weight_q14);
  EXPECT_LT(largest, 32768);
  EXPECT_LT(max_deviation_mm(arc, f), 0.0008);  // control points are whole um
}

// The Q14 weights of the widest search: the scale m in [32768, 65535] of the largest weight
// with the least worst relative rounding error (the first found from the top), as the
// converter falls back to for long legs.
std::vector<uint16_t> best_q14_weights(const std::vector<double>& w) {
  const double w_max = *std::max_element(w.begin(), w.end());
  long best_m = 65535;
  double best_err = 1e300;
  for (long m = 65535; m >= 32768; --m) {
    double err = 0;
    for (double x : w) {
      const double q = std::floor(x * m / w_max + 0.5);
      err = std::max(err, std::fabs(q - x * m / w_max) / q);
    }
    if (err < best_err) best_err = err, best_m = m;
    if (err < 1e-9) break;
  }
  std::vector<uint16_t> q;
  for (double x : w) q.push_back(static_cast<uint16_t>(std::floor(x * best_m / w_max + 0.5)));
  return q;
}

TEST(FirmwareSpline, CircleWeightsAreScaledToQ14WithinRoundingOfTheirRatio) {
  const BSpline circle = arc_spline({50, 50}, 40.0, 0, 2 * kPi);
  const std::vector<core::Spline> f = to_firmware_splines(circle);
  ASSERT_EQ(f.size(), 1u);
  ASSERT_TRUE(f[0].rational);
  const double ratio = static_cast<double>(f[0].control[1].weight_q14) / f[0].control[0].weight_q14;
  // The coarsest grid that keeps the 40 mm legs within 0.25 um: relative error <= 6.25e-6.
  EXPECT_NEAR(ratio, std::cos(kPi / 4), 6.25e-6 * 2);
  // A 40 mm circle stays within a micrometre of the exact one.
  EXPECT_LT(max_deviation_mm(circle, f), 0.001);
  // The scale searched for these weights is kept, and a third of a circle converted between
  // (two 60 deg pieces: other weights) gets its own: each the scale the search finds.
  const BSpline third = arc_spline({50, 50}, 40.0, 0, 2 * kPi / 3);
  const std::vector<core::Spline> t = to_firmware_splines(third);
  const std::vector<core::Spline> again = to_firmware_splines(circle);
  ASSERT_EQ(again.size(), 1u);
  ASSERT_FALSE(t.empty());
  const std::vector<uint16_t> want_circle = best_q14_weights(circle.weights);
  const std::vector<uint16_t> want_third = best_q14_weights(
      std::vector<double>(third.weights.begin(), third.weights.begin() + t[0].control_count));
  for (int i = 0; i < f[0].control_count; ++i) {
    EXPECT_EQ(f[0].control[i].weight_q14, want_circle[i]) << i;
    EXPECT_EQ(again[0].control[i].weight_q14, want_circle[i]) << i;
  }
  for (int i = 0; i < t[0].control_count; ++i)
    EXPECT_EQ(t[0].control[i].weight_q14, want_third[i]) << i;
}

TEST(FirmwareSpline, CurveWithMoreThan64ControlPointsIsSplitWithoutChangingShape) {
  BSpline s;
  s.degree = 3;
  for (int i = 0; i < 150; ++i) s.control.emplace_back(i * 1.0, 10.0 * std::sin(i * 0.3));
  s.knots = {0, 0, 0, 0};
  for (int i = 1; i <= 146; ++i) s.knots.push_back(i);
  s.knots.insert(s.knots.end(), 4, 147);
  const std::vector<core::Spline> f = to_firmware_splines(s);
  ASSERT_GE(f.size(), 3u);
  for (size_t k = 0; k < f.size(); ++k) {
    EXPECT_LE(f[k].control_count, core::kMaxControlPoints);
    EXPECT_EQ(core::validate_spline(f[k]), core::GeometryError::kOk);
    if (k > 0) {  // pieces join end to start
      EXPECT_EQ(f[k].control[0].x_um, f[k - 1].control[f[k - 1].control_count - 1].x_um);
      EXPECT_EQ(f[k].control[0].y_um, f[k - 1].control[f[k - 1].control_count - 1].y_um);
    }
  }
  EXPECT_LT(max_deviation_mm(s, f), 0.001);
  EXPECT_LT((start_point(from_firmware_spline(f.front())) - start_point(s)).norm(), 0.001);
  EXPECT_LT((end_point(from_firmware_spline(f.back())) - end_point(s)).norm(), 0.001);
}

// A DXF contour of chained LINEs is one polyline of any length: its pieces are slices of it
// that keep every vertex, in order, each joined to the next at a shared vertex.
TEST(FirmwareSpline, LongPolylineIsSlicedAtItsVertices) {
  BSpline s;
  s.degree = 1;
  const int n = 20000;
  for (int i = 0; i < n; ++i) s.control.emplace_back(0.01 * i, 5.0 + 3.0 * std::sin(i * 0.01));
  s.knots.push_back(0);
  for (int i = 0; i < n; ++i) s.knots.push_back(i);
  s.knots.push_back(n - 1);
  const std::vector<core::Spline> f = to_firmware_splines(s);
  ASSERT_EQ(f.size(), static_cast<size_t>((n - 1 + core::kMaxControlPoints - 2) /
                                          (core::kMaxControlPoints - 1)));
  size_t vertex = 0;
  for (size_t k = 0; k < f.size(); ++k) {
    EXPECT_EQ(core::validate_spline(f[k]), core::GeometryError::kOk);
    if (k > 0) --vertex;  // the joint is the previous piece's last vertex
    for (int i = 0; i < f[k].control_count; ++i, ++vertex) {
      ASSERT_EQ(f[k].control[i].x_um, std::lround(s.control[vertex].x() * 1000)) << k << " " << i;
      ASSERT_EQ(f[k].control[i].y_um, std::lround(s.control[vertex].y() * 1000)) << k << " " << i;
    }
  }
  EXPECT_EQ(vertex, static_cast<size_t>(n));
}

// A long rational cubic with single, double and triple knots: cut where it passes through a
// control point already, or where knots are inserted, without changing the shape.
TEST(FirmwareSpline, LongRationalCubicWithMixedKnotsIsSplitWithoutChangingShape) {
  BSpline s;
  s.degree = 3;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    s.control.emplace_back(0.3 * i, 20.0 + 8.0 * std::sin(i * 0.17) + (i % 7 == 0 ? 2.0 : 0.0));
    s.weights.push_back(1.0 + 0.4 * std::sin(i * 0.23));
  }
  s.knots.assign(4, 0.0);
  double t = 0;
  while (s.knots.size() < static_cast<size_t>(n)) {
    t += 1.0 + 0.5 * std::sin(t);
    const size_t copies = s.knots.size() % 37 == 0 ? 3 : (s.knots.size() % 11 == 0 ? 2 : 1);
    for (size_t c = 0; c < copies && s.knots.size() < static_cast<size_t>(n); ++c)
      s.knots.push_back(t);
  }
  s.knots.insert(s.knots.end(), 4, t + 1.0);
  ASSERT_EQ(check_bspline(s), "");
  const std::vector<core::Spline> f = to_firmware_splines(s);
  ASSERT_GE(f.size(), 5u);
  for (size_t k = 0; k < f.size(); ++k) {
    EXPECT_LE(f[k].control_count, core::kMaxControlPoints);
    EXPECT_EQ(core::validate_spline(f[k]), core::GeometryError::kOk);
    if (k > 0) {
      EXPECT_EQ(f[k].control[0].x_um, f[k - 1].control[f[k - 1].control_count - 1].x_um);
      EXPECT_EQ(f[k].control[0].y_um, f[k - 1].control[f[k - 1].control_count - 1].y_um);
    }
  }
  EXPECT_LT(max_deviation_mm(s, f), 0.001);
  EXPECT_LT((start_point(from_firmware_spline(f.front())) - start_point(s)).norm(), 0.001);
  EXPECT_LT((end_point(from_firmware_spline(f.back())) - end_point(s)).norm(), 0.001);
}

TEST(FirmwareSpline, CoordinateBeyondOneMetreIsRefused) {
  const BSpline s = line_spline({0, 0}, {1500, 0});
  try {
    to_firmware_splines(s);
    FAIL();
  } catch (const ConversionError& e) {
    EXPECT_NE(std::string(e.what()).find("control point 1 (1500, 0) mm"), std::string::npos)
        << e.what();
  }
}

TEST(FirmwareSpline, ReversedCurveConvertsToTheSameShape) {
  BSpline s;
  s.degree = 2;
  s.control = {{0, 0}, {5, 10}, {10, 0}, {20, 5}};
  s.weights = {1, 2, 0.5, 1};
  s.knots = {0, 0, 0, 0.3, 1, 1, 1};
  const BSpline r = reversed(s);
  EXPECT_LT(max_deviation_mm(r, to_firmware_splines(r)), 0.001);  // r == s: bspline_test
  EXPECT_LT((start_point(from_firmware_spline(to_firmware_splines(r)[0])) - end_point(s)).norm(),
            0.001);
}

}  // namespace
}  // namespace host
