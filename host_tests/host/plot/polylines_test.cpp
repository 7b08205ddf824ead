// The plot's flat polyline list: each polyline back as it went in (to a float's step), and
// a two-point line in about 20 bytes.
#include "host/lib/plot/polylines.h"

#include <gtest/gtest.h>

#include <vector>  // std::vector

namespace host {
namespace {

TEST(Polylines, EachPolylineComesBackInOrder) {
  Polylines lines;
  lines.push_back({{0, 0}, {100, 0}, {100, 50}});
  lines.push_back({});
  lines.push_back({{0.1234567, -250.5}});
  ASSERT_EQ(lines.size(), 3u);
  std::vector<std::vector<Point2>> got;
  lines.each([&got](const std::vector<Point2>& l) { got.push_back(l); });
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], (std::vector<Point2>{{0, 0}, {100, 0}, {100, 50}}));
  EXPECT_TRUE(got[1].empty());
  ASSERT_EQ(got[2].size(), 1u);
  EXPECT_NEAR(got[2][0].x(), 0.1234567, 1e-7);  // float mm: far below a pixel
  EXPECT_EQ(got[2][0].y(), -250.5);
  EXPECT_TRUE(Polylines().empty());
}

TEST(Polylines, ALineTakesAboutTwentyBytes) {
  Polylines lines;
  const size_t n = 100000;
  lines.reserve(n);
  for (size_t i = 0; i < n; ++i) lines.push_back({Point2(i, 0), Point2(i, 1)});
  EXPECT_LE(lines.heap_bytes(), n * (4 + 2 * 8 * 2));  // starts, and points at most doubled
  size_t count = 0;
  lines.each([&count](const std::vector<Point2>& l) { count += l.size(); });
  EXPECT_EQ(count, 2 * n);
}

}  // namespace
}  // namespace host
