// Cubic B-spline fits of G1 runs: within tolerance both ways, fewer control points than
// segments, corners and long segments kept, the pieces joined end to start.
#include "host/lib/plan/polyline_fit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace host {
namespace {

const double kPi = 3.14159265358979323846;

// An arc of radius r through n + 1 points (the way CAM programs write arcs as G1 moves).
std::vector<Point2> arc_points(Point2 c, double r, double a0, double a1, int n) {
  std::vector<Point2> p;
  for (int i = 0; i <= n; ++i) {
    const double a = a0 + (a1 - a0) * i / n;
    p.push_back(c + r * Point2(std::cos(a), std::sin(a)));
  }
  return p;
}

double distance_to_polyline(const Point2& q, const std::vector<Point2>& p) {
  double best = 1e300;
  for (size_t i = 1; i < p.size(); ++i) {
    const Point2 ab = p[i] - p[i - 1];
    const double s = std::max(0.0, std::min(1.0, (q - p[i - 1]).dot(ab) / ab.squaredNorm()));
    best = std::min(best, (q - (p[i - 1] + s * ab)).norm());
  }
  return best;
}

// Largest distance from the pieces (densely sampled) to the polyline and back.
double hausdorff(const std::vector<BSpline>& pieces, const std::vector<Point2>& p) {
  std::vector<Point2> curve;
  for (const BSpline& s : pieces) {
    for (int i = 0; i <= 2000; ++i)
      curve.push_back(evaluate(s, s.t_min() + (s.t_max() - s.t_min()) * i / 2000.0));
  }
  double worst = 0;
  for (const Point2& q : curve) worst = std::max(worst, distance_to_polyline(q, p));
  for (const Point2& v : p) {
    double best = 1e300;
    for (const Point2& q : curve) best = std::min(best, (q - v).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(PolylineFit, AnArcOfShortMovesBecomesOneCubicWithinTolerance) {
  const std::vector<Point2> p = arc_points({0, 0}, 5, 0, kPi, 60);  // 0.26 mm moves
  FitOptions o;
  const std::vector<BSpline> pieces = fit_polyline(p, o);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].degree, 3);
  EXPECT_LT(pieces[0].control.size(), 30u);  // far fewer than 60 moves
  EXPECT_LT(hausdorff(pieces, p), o.tolerance_mm + 0.0005);
  EXPECT_LT((start_point(pieces[0]) - p.front()).norm(), 1e-12);
  EXPECT_LT((end_point(pieces[0]) - p.back()).norm(), 1e-12);
}

TEST(PolylineFit, CornersAndLongSegmentsStayAsTheyAre) {
  // Short moves up a quarter arc, a sharp corner, a 10 mm straight, then another arc.
  std::vector<Point2> p = arc_points({0, 0}, 5, 0, kPi / 2, 30);
  p.push_back(Point2(-10, 5));
  const std::vector<Point2> back = arc_points({-10, 0}, 5, kPi / 2, kPi, 30);
  p.insert(p.end(), back.begin() + 1, back.end());
  const std::vector<BSpline> pieces = fit_polyline(p, FitOptions());
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].degree, 3);
  EXPECT_EQ(pieces[1].degree, 1);  // the long straight, corner to corner
  EXPECT_EQ(pieces[1].control.size(), 2u);
  EXPECT_EQ(pieces[2].degree, 3);
  for (size_t i = 1; i < pieces.size(); ++i)
    EXPECT_LT((start_point(pieces[i]) - end_point(pieces[i - 1])).norm(), 1e-12);
  EXPECT_LT(hausdorff(pieces, p), 0.0055);
}

TEST(PolylineFit, ATighterToleranceNeedsMoreControlPoints) {
  const std::vector<Point2> p = arc_points({0, 0}, 20, 0, 1.5, 100);
  FitOptions loose, tight;
  loose.tolerance_mm = 0.01;
  tight.tolerance_mm = 0.0005;
  const std::vector<BSpline> a = fit_polyline(p, loose), b = fit_polyline(p, tight);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  size_t ca = 0, cb = 0;
  for (const BSpline& s : a) ca += s.control.size();
  for (const BSpline& s : b) cb += s.control.size();
  EXPECT_LT(ca, cb);
  EXPECT_LT(hausdorff(b, p), 0.0005 + 0.0001);
}

TEST(PolylineFit, NoiseThatCannotBeFittedStaysStraight) {
  // A zigzag of 0.1 mm moves turning 23 degrees: no corner, but no smooth fit within 1 um.
  std::vector<Point2> p;
  for (int i = 0; i <= 20; ++i) p.push_back(Point2(0.1 * i, (i % 2) * 0.02));
  FitOptions o;
  o.tolerance_mm = 0.001;
  const std::vector<BSpline> pieces = fit_polyline(p, o);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].degree, 1);
  EXPECT_EQ(pieces[0].control.size(), p.size());
}

}  // namespace
}  // namespace host
