// The contour error's nearest-segment index: exact against a brute-force search on sparse,
// dense and mixed segments, and a dense contour's query looks at a few segments, not at
// every segment of its grid cell.
#include <gtest/gtest.h>

#include <cmath>   // std::cos, std::sin
#include <limits>  // std::numeric_limits
#include <random>  // std::mt19937

#include "host/lib/sim/contour_error.h"

namespace host::sim {
namespace {

// Plain doubles: Eigen in a Debug build made this test take a minute.
double brute_force(const std::vector<std::vector<Point2>>& lines, const Point2& p) {
  double best2 = std::numeric_limits<double>::infinity();
  const double px = p.x(), py = p.y();
  for (const auto& line : lines) {
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      const double ax = line[i].x(), ay = line[i].y();
      const double abx = line[i + 1].x() - ax, aby = line[i + 1].y() - ay;
      const double len2 = abx * abx + aby * aby;
      double t = len2 > 0 ? ((px - ax) * abx + (py - ay) * aby) / len2 : 0.0;
      t = std::min(1.0, std::max(0.0, t));
      const double dx = ax + t * abx - px, dy = ay + t * aby - py;
      best2 = std::min(best2, dx * dx + dy * dy);
    }
  }
  return std::sqrt(best2);
}

// A ring of n segments about (cx, cy).
std::vector<Point2> ring(int n, double cx, double cy, double r) {
  std::vector<Point2> out;
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * M_PI * i / n;
    out.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a));
  }
  return out;
}

void expect_exact(const std::vector<std::vector<Point2>>& lines, const std::vector<Point2>& at) {
  const NearestSegment index(lines);
  if (lines.size() > 1 && lines[0].size() > 1000) EXPECT_GT(index.fine_cell_mm(), 0.0);
  for (const Point2& p : at)
    EXPECT_NEAR(index.distance(p), brute_force(lines, p), 1e-12) << p.transpose();
}

TEST(NearestSegment, ExactOnSparseLongSegments) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 100);
  std::vector<std::vector<Point2>> lines;
  for (int i = 0; i < 200; ++i) lines.push_back({Point2(u(rng), u(rng)), Point2(u(rng), u(rng))});
  std::vector<Point2> at;
  for (int i = 0; i < 300; ++i) at.emplace_back(u(rng) * 1.2 - 10, u(rng) * 1.2 - 10);
  expect_exact(lines, at);
}

TEST(NearestSegment, ExactOnADenseContourWithLongLinesBesideIt) {
  // 8 000 segments of ~8 um (the fine grid) and a few long lines crossing it (the coarse
  // grid's long segments); points on, near and far from both.
  std::vector<std::vector<Point2>> lines = {ring(8000, 20, 20, 10)};
  lines.push_back({Point2(5, 20), Point2(35, 20.0005)});
  lines.push_back({Point2(20, 5), Point2(20.002, 35)});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), off(-0.01, 0.01), far(-30, 60);
  std::vector<Point2> at;
  for (int i = 0; i < 400; ++i) {
    const double a = angle(rng), r = 10 + off(rng);
    at.emplace_back(20 + r * std::cos(a), 20 + r * std::sin(a));
  }
  for (int i = 0; i < 100; ++i) at.emplace_back(far(rng), far(rng));
  for (int i = 0; i < 100; ++i) at.emplace_back(20 + off(rng), 20 + far(rng) / 3);
  expect_exact(lines, at);
}

TEST(NearestSegment, ADenseContoursQueryLooksAtAFewSegments) {
  // 200 000 segments of 0.3 um on a 10 mm ring: ~1 600 per 0.5 mm cell. A tool following
  // the ring within a micrometre must not look at all of them at every sample.
  const std::vector<std::vector<Point2>> lines = {ring(200000, 20, 20, 10)};
  const NearestSegment index(lines);
  EXPECT_GT(index.fine_cell_mm(), 0.0);
  const int queries = 2000;
  const size_t before = index.segments_examined();
  for (int i = 0; i < queries; ++i) {
    const double a = 2 * M_PI * i / queries, r = 10 + 0.001 * std::sin(7 * a);
    index.distance(Point2(20 + r * std::cos(a), 20 + r * std::sin(a)));
  }
  const double per_query = double(index.segments_examined() - before) / queries;
  EXPECT_LT(per_query, 100.0);
}

TEST(NearestSegment, ExactOnShortLinesAtEveryAngle) {
  // Lines of 0.5-5 mm (1-10 cells) at random angles, as the big-job test file scatters them:
  // each is listed only in the cells it crosses, and points near any of them still find it.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(0, 40), len(0.5, 5), angle(0, 2 * M_PI), off(-0.3, 0.3);
  std::vector<std::vector<Point2>> lines;
  std::vector<Point2> at;
  for (int i = 0; i < 400; ++i) {
    const Point2 a(x(rng), x(rng));
    const double l = len(rng), t = angle(rng);
    lines.push_back({a, a + l * Point2(std::cos(t), std::sin(t))});
    at.push_back(a + 0.5 * l * Point2(std::cos(t), std::sin(t)) + Point2(off(rng), off(rng)));
  }
  lines.push_back({Point2(0, 0), Point2(40, 40)});  // on the cells' corners all the way
  lines.push_back({Point2(1, 3), Point2(39, 3)});   // along a row of cell edges
  for (int i = 0; i < 300; ++i) at.emplace_back(x(rng), x(rng));
  for (int i = 0; i <= 80; ++i) at.emplace_back(0.5 * i + 1e-7, 0.5 * i - 1e-7);
  expect_exact(lines, at);
}

TEST(NearestSegment, AShortLineIsListedInTheCellsItCrossesNotItsBoundingBox) {
  // 100 000 random lines of 0.5-5 mm over a 280 x 190 mm area (tools/bigjob's `lines`): a
  // million of them held 70 MB of cell lists when each was listed in every cell of its
  // bounding box (~18 a line); the cells it crosses are ~8.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(5, 290), y(5, 200), len(0.5, 5), angle(0, 2 * M_PI);
  const int n = 100000;
  NearestSegment index;
  index.reserve(n);
  for (int i = 0; i < n; ++i) {
    const Point2 a(x(rng), y(rng));
    const double l = len(rng), t = angle(rng);
    index.add({a, a + l * Point2(std::cos(t), std::sin(t))});
  }
  index.index();
  EXPECT_EQ(index.fine_cell_mm(), 0.0);  // the coarse grid only
  RecordProperty("held_bytes_per_line", static_cast<int>(index.held_bytes() / n));
  EXPECT_LE(index.held_bytes(), 80u * n) << index.held_bytes() / n << " bytes a line";
}

}  // namespace
}  // namespace host::sim
