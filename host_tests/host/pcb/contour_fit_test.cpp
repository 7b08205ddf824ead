// Polyline -> lines, exact arcs and cubic fits: shapes, tolerances, firmware form.
#include "host/lib/pcb/contour_fit.h"

#include <gtest/gtest.h>

#include <cmath>  // std::sin

#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/firmware_spline.h"
#include "host_tests/host/pcb/synthetic_board.h"

namespace host::pcb {
namespace {

std::vector<Point2> mm_points(const ClipperLib::Path& p) {
  std::vector<Point2> out;
  for (const auto& q : p) out.push_back(to_mm(q));
  return out;
}

const double kTol = 0.002;

TEST(ContourFit, SquareIsFourLinesInOneDegreeOneSpline) {
  FitStats st;
  const std::vector<Point2> sq = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const std::vector<BSpline> c = fit_polyline(sq, true, FitOptions(), &st);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].degree, 1);
  EXPECT_EQ(st.lines, 4);
  EXPECT_EQ(st.arcs, 0);
  EXPECT_EQ(c[0].control.size(), 5u);  // closed: back to the start
  EXPECT_LT((start_point(c[0]) - end_point(c[0])).norm(), 1e-12);
  EXPECT_LT(max_deviation_mm(sq, true, c), 1e-9);
}

TEST(ContourFit, FlattenedCircleBecomesOneExactRationalArc) {
  // Clipper's round offset of a point-like square: vertices on a 1.1 mm circle.
  const ClipperLib::Paths circle =
      offset_closed({test::rect(-0.0001, -0.0001, 0.0001, 0.0001)}, 1.1e6, 1000);
  ASSERT_EQ(circle.size(), 1u);
  const std::vector<Point2> pts = mm_points(circle[0]);
  ASSERT_GT(pts.size(), 30u);
  FitStats st;
  FitOptions fo;
  fo.tolerance_mm = kTol;
  const std::vector<BSpline> c = fit_polyline(pts, true, fo, &st);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].degree, 2);
  EXPECT_TRUE(c[0].rational());
  EXPECT_GE(st.arcs, 1);
  EXPECT_LE(st.arcs, 2);                // the start may cut the circle once
  EXPECT_LE(c[0].control.size(), 13u);  // at most 6 quarter pieces, far fewer than vertices
  // Every point of the curve on the circle (within the fit tolerance).
  for (const Point2& p : sample(c[0], 0.0005)) EXPECT_NEAR(p.norm(), 1.1001, kTol + 0.0002);
  EXPECT_LE(max_deviation_mm(pts, true, c), kTol);
}

TEST(ContourFit, RoundedRectangleIsFourLinesAndFourArcs) {
  const ClipperLib::Paths rr = offset_closed({test::rect(0, 0, 5, 2)}, 0.5e6, 1000);
  ASSERT_EQ(rr.size(), 1u);
  const std::vector<Point2> pts = mm_points(rr[0]);
  FitStats st;
  const std::vector<BSpline> c = fit_polyline(pts, true, FitOptions(), &st);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(st.lines, 4);
  EXPECT_EQ(st.arcs, 4);
  EXPECT_EQ(st.cubics, 0);
  EXPECT_LE(max_deviation_mm(pts, true, c), FitOptions().tolerance_mm);
  // The firmware takes it (64 control points at most, weights, knots).
  const std::vector<core::Spline> fw = to_firmware_splines(c[0]);
  EXPECT_EQ(fw.size(), 1u);
}

TEST(ContourFit, WavyRunOfShortSegmentsIsFittedWithACubicWithinTolerance) {
  std::vector<Point2> wave;
  for (int i = 0; i <= 200; ++i) {
    const double x = i * 0.05;
    wave.emplace_back(x, 0.8 * std::sin(x * 0.9) + 0.3 * std::sin(x * 2.1));
  }
  FitStats st;
  FitOptions fo;
  fo.tolerance_mm = kTol;
  const std::vector<BSpline> c = fit_polyline(wave, false, fo, &st);
  EXPECT_GE(st.cubics, 1);
  size_t controls = 0;
  for (const BSpline& b : c) controls += b.control.size();
  EXPECT_LT(controls, wave.size() / 3);
  EXPECT_LE(max_deviation_mm(wave, false, c), kTol * 1.01);
  EXPECT_LT((start_point(c.front()) - wave.front()).norm(), 1e-9);
  EXPECT_LT((end_point(c.back()) - wave.back()).norm(), 1e-9);
}

TEST(ContourFit, ASquaresCornersAreNotMistakenForACircle) {
  // Four vertices lie on a circle, but the edges' midpoints are far from it.
  FitStats st;
  const std::vector<Point2> sq = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {-0.2, 0.5}};
  fit_polyline(sq, true, FitOptions(), &st);
  EXPECT_EQ(st.arcs, 0);
}

// An arc turns at most once around (its sweep is checked without an atan2 per chord, then
// summed exactly): a run once round its circle is one arc, a run one and a half times
// round is two.
TEST(ContourFit, AnArcTurnsAtMostOnceAround) {
  const double r = 20, step = 2 * 3.14159265358979323846 / 240;  // sagitta 1.7 um
  auto around = [&](int segments) {
    std::vector<Point2> run;
    for (int k = 0; k <= segments; ++k)
      run.push_back(Point2(r * std::cos(k * step), r * std::sin(k * step)));
    return run;
  };
  for (const int segments : {240, 360}) {
    SCOPED_TRACE(segments);
    const std::vector<Point2> run = around(segments);
    FitStats st;
    const std::vector<BSpline> c = fit_polyline(run, false, FitOptions(), &st);
    EXPECT_EQ(st.lines, 0);
    EXPECT_EQ(st.cubics, 0);
    EXPECT_EQ(st.arcs, segments == 240 ? 1 : 2);
    EXPECT_LE(max_deviation_mm(run, false, c), kTol);
  }
}

// The other direction of the tolerance: the fitted curve stays within it of the polyline, also
// between the vertices. Chords whose sagitta against their circle is 4 um (tolerance 2 um)
// must not become that circle: it would bow 4 um off every chord (on easy-sdr such arcs took
// the planned isolation paths 6.7 um toward the copper).
TEST(ContourFit, ChordsCoarserThanTheToleranceAreNotReplacedByTheirCircle) {
  const double r = 1.0, sagitta = 0.004;
  const double step = 2 * std::acos(1 - sagitta / r);  // chord angle with that sagitta
  std::vector<Point2> arc;
  for (int k = 0; k <= 9; ++k)
    arc.push_back(Point2(r * std::cos(k * step), r * std::sin(k * step)));
  FitOptions fo;
  fo.tolerance_mm = kTol;
  FitStats st;
  const std::vector<BSpline> c = fit_polyline(arc, false, fo, &st);
  EXPECT_EQ(st.arcs, 0);
  double worst = 0;
  for (const BSpline& b : c) {
    for (const Point2& x : sample(b, 0.0001)) {
      double best = 1e9;
      for (size_t k = 0; k + 1 < arc.size(); ++k) {
        const Point2 d = arc[k + 1] - arc[k];
        const double f = std::max(0.0, std::min(1.0, (x - arc[k]).dot(d) / d.squaredNorm()));
        best = std::min(best, (arc[k] + d * f - x).norm());
      }
      worst = std::max(worst, best);
    }
  }
  EXPECT_LE(worst, kTol + 1e-6);
}

}  // namespace
}  // namespace host::pcb
