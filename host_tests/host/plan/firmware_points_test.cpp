// The points the firmware core generates (run on the host) against Eigen in double: every
// point within 1 um of the curve at its parameter neighbourhood, chords within tolerance.
#include "host/lib/plan/firmware_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "host/lib/drawing/conics.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/firmware_spline.h"
#include "host_tests/host/drawing/eigen_reference.h"

namespace host {
namespace {

const double kPi = 3.14159265358979323846;

// Dense reference polyline of the firmware spline by Eigen (double precision): n points per
// knot span, span ends included (corners at knots are exact vertices).
std::vector<Point2> eigen_dense(const core::Spline& f, int n) {
  const BSpline b = from_firmware_spline(f);
  std::vector<Point2> out;
  for (size_t k = b.degree; k < b.control.size(); ++k) {
    const double t0 = b.knots[k], t1 = b.knots[k + 1];
    if (!(t1 > t0)) continue;
    for (int i = 0; i <= n; ++i) out.push_back(test::eigen_point(b, t0 + (t1 - t0) * i / n));
  }
  return out;
}

// Distance from p to a polyline (nearest segment anywhere on it).
double distance(const Point2& p, const std::vector<Point2>& line) {
  double best = 1e300;
  for (size_t k = 1; k < line.size(); ++k) {
    const Point2 d = line[k] - line[k - 1];
    const double len2 = d.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - line[k - 1]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (line[k - 1] + u * d - p).norm());
  }
  return best;
}

struct Stats {
  double max_point_error_um = 0;  // firmware point to the Eigen curve
  double max_chord_error_um = 0;  // Eigen curve between two points to their chord
  size_t points = 0;
};

// Runs the curve walker on every piece of the curve and measures it against Eigen.
Stats measure(const BSpline& curve, int tol_um) {
  Stats st;
  for (const core::Spline& f : to_firmware_splines(curve)) {
    const std::vector<core::PointUm> pts = firmware_points_um({f}, tol_um);
    const std::vector<Point2> dense = eigen_dense(f, 1000);
    std::vector<Point2> mm;
    for (const core::PointUm& p : pts) mm.emplace_back(p.x_um / 1000.0, p.y_um / 1000.0);
    for (const Point2& p : mm) {
      st.max_point_error_um = std::max(st.max_point_error_um, 1000 * distance(p, dense));
    }
    // Chord error: each dense curve point against the polyline of the firmware points.
    for (const Point2& q : dense) {
      st.max_chord_error_um = std::max(st.max_chord_error_um, 1000 * distance(q, mm));
    }
    st.points += pts.size();
  }
  return st;
}

TEST(FirmwarePoints, CubicPointsWithin1umOfEigenAndChordsWithinTolerance) {
  BSpline s;
  s.degree = 3;
  s.control = {{0, 0}, {10, 30}, {35, 35}, {50, 0}, {60, -20}, {80, 10}};
  s.knots = {0, 0, 0, 0, 1, 2.5, 4, 4, 4, 4};
  const Stats st = measure(s, 5);
  EXPECT_LE(st.max_point_error_um, 1.0);
  EXPECT_LE(st.max_chord_error_um, 5.0 + 1.0);  // tolerance + the 1 um output rounding
  EXPECT_GT(st.points, 20u);
}

TEST(FirmwarePoints, RationalCirclePointsWithin1umOfEigen) {
  const Stats st = measure(arc_spline({100, 100}, 25.0, 0, 2 * kPi), 5);
  EXPECT_LE(st.max_point_error_um, 1.0);
  EXPECT_LE(st.max_chord_error_um, 6.0);
}

TEST(FirmwarePoints, CoarserToleranceGivesFewerPointsAndStillHoldsIt) {
  const BSpline c = arc_spline({0, 0}, 10.0, 0, kPi);
  const Stats fine = measure(c, 5);
  const Stats coarse = measure(c, 50);
  EXPECT_LT(coarse.points, fine.points);
  EXPECT_LE(coarse.max_chord_error_um, 51.0);
  EXPECT_LE(coarse.max_point_error_um, 1.0);
}

TEST(FirmwarePoints, BundledSampleEveryCurveWithin1umAndTolerance) {
  const Drawing d = import_drawing(std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf");
  Stats worst;
  for (size_t i = 0; i < d.curves.size(); ++i) {
    const Stats st = measure(d.curves[i].spline(), 5);
    EXPECT_LE(st.max_point_error_um, 1.0) << "curve " << i;
    EXPECT_LE(st.max_chord_error_um, 6.0) << "curve " << i;
    worst.max_point_error_um = std::max(worst.max_point_error_um, st.max_point_error_um);
    worst.max_chord_error_um = std::max(worst.max_chord_error_um, st.max_chord_error_um);
    worst.points += st.points;
  }
  RecordProperty("points", static_cast<int>(worst.points));
  std::printf("sample at 5 um: %zu points, worst point error %.3f um, worst chord error %.3f um\n",
              worst.points, worst.max_point_error_um, worst.max_chord_error_um);
}

TEST(FirmwarePoints, FirstAndLastPointsAreTheCurveEnds) {
  BSpline s;
  s.degree = 2;
  s.control = {{1, 1}, {5, 9}, {9, 1}};
  s.knots = {-2, -2, -2, 3, 3, 3};
  const std::vector<Point2> p = firmware_points_mm(s, 5);
  ASSERT_GE(p.size(), 2u);
  EXPECT_LT((p.front() - Point2(1, 1)).norm(), 0.0011);
  EXPECT_LT((p.back() - Point2(9, 1)).norm(), 0.0011);
}

}  // namespace
}  // namespace host
