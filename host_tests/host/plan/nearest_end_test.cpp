// The grid search of the greedy ordering finds what a scan over every curve finds, ties
// included (the lowest index, the start before the end), as curves are used up.
#include <gtest/gtest.h>

#include <random>  // std::mt19937

#include "host/lib/plan/nearest_end.h"

namespace host {
namespace {

NearestEnd::Hit scan(const std::vector<Point2>& s, const std::vector<Point2>& e,
                     const std::vector<bool>& used, const Point2& p) {
  NearestEnd::Hit best;
  for (size_t i = 0; i < s.size(); ++i) {
    if (used[i]) continue;
    const double ds = (s[i] - p).norm(), de = (e[i] - p).norm();
    if (ds < best.distance) best = NearestEnd::Hit{i, false, ds};
    if (de < best.distance) best = NearestEnd::Hit{i, true, de};
  }
  return best;
}

// Walks the greedy order both ways and compares every step.
void check_same_order(const std::vector<Point2>& s, const std::vector<Point2>& e) {
  NearestEnd grid(s, e);
  std::vector<bool> used(s.size(), false);
  Point2 at(0, 0);
  for (size_t n = 0; n < s.size(); ++n) {
    const NearestEnd::Hit want = scan(s, e, used, at);
    const NearestEnd::Hit got = grid.nearest(at);
    ASSERT_EQ(got.index, want.index) << "step " << n;
    ASSERT_EQ(got.reversed, want.reversed) << "step " << n;
    ASSERT_DOUBLE_EQ(got.distance, want.distance) << "step " << n;
    used[got.index] = true;
    grid.use(got.index);
    at = got.reversed ? s[got.index] : e[got.index];
  }
  EXPECT_EQ(grid.nearest(at).distance, 1e300);
}

TEST(NearestEnd, RandomLinesInTheSameOrderAsAFullScan) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 200), d(-3, 3);
  std::vector<Point2> s, e;
  for (int i = 0; i < 2000; ++i) {
    s.emplace_back(u(rng), u(rng) * 0.7);
    e.push_back(s.back() + Point2(d(rng), d(rng)));
  }
  check_same_order(s, e);
}

TEST(NearestEnd, ChainedContourAndExactTiesAsAFullScan) {
  // A closed ring of segments (every end shared by two curves), points on a lattice (many
  // exact ties) and a far-away cluster (rings grow over empty cells).
  std::vector<Point2> s, e;
  for (int i = 0; i < 300; ++i) {
    const double a = 2 * M_PI * i / 300, b = 2 * M_PI * (i + 1) / 300;
    s.emplace_back(50 + 20 * std::cos(a), 50 + 20 * std::sin(a));
    e.emplace_back(50 + 20 * std::cos(b), 50 + 20 * std::sin(b));
  }
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 10; ++j) {
      s.emplace_back(100 + i, j);
      e.emplace_back(100 + i, j + 1);
    }
  }
  s.emplace_back(900, 900);
  e.emplace_back(901, 900);
  check_same_order(s, e);
}

TEST(NearestEnd, HoldsAboutSixteenBytesACurveAndNoCopyOfTheEnds) {
  // 100 000 separate lines: a vector per cell and a copy of the ends held ~90 bytes a curve
  // (a million-line job: ~90 MB beside the drawing while it was ordered).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 280), d(-2, 2);
  std::vector<Point2> s, e;
  for (int i = 0; i < 100000; ++i) {
    s.emplace_back(u(rng), u(rng) * 0.7);
    e.push_back(s.back() + Point2(d(rng), d(rng)));
  }
  NearestEnd grid(s, e);
  EXPECT_LE(grid.held_bytes(), 20u * s.size());
}

}  // namespace
}  // namespace host
