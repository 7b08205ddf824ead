// Drill grouping by diameter and travel ordering.
#include "host/lib/pcb/drill_order.h"

#include <gtest/gtest.h>

#include <algorithm>  // std::sort

namespace host::pcb {
namespace {

TEST(DrillOrder, HolesOnALineInShuffledOrderAreDrilledEndToEnd) {
  const std::vector<Point2> at = {{5, 0}, {1, 0}, {9, 0}, {3, 0}, {7, 0}, {2, 0}, {8, 0}};
  const DrillPlan p = order_holes(at, std::vector<double>(at.size(), 0.8),
                                  std::vector<int>(at.size(), 1), Point2(0, 0));
  ASSERT_EQ(p.groups.size(), 1u);
  EXPECT_NEAR(p.travel_ordered_mm, 9.0, 1e-9);  // straight out along the line
  EXPECT_NEAR(p.travel_file_order_mm, 5 + 4 + 8 + 6 + 4 + 5 + 6, 1e-9);
}

TEST(DrillOrder, TwoOptRemovesACrossingThatNearestNeighbourLeaves) {
  // A grid in scrambled order: the ordered tour never crosses itself, so it is shorter
  // than nearest neighbour alone would be and far shorter than the file order.
  std::vector<Point2> at;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) at.emplace_back(((i * 7) % 10) * 2.54, ((j * 3) % 10) * 2.54);
  const std::vector<size_t> tour = short_tour(Point2(0, 0), at);
  std::vector<size_t> sorted = tour;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) EXPECT_EQ(sorted[i], i);  // every hole once
  std::vector<Point2> ordered;
  for (size_t k : tour) ordered.push_back(at[k]);
  // 100 holes at 2.54 mm pitch: a boustrophedon visits them in 99 steps of 2.54 mm.
  EXPECT_LE(travel_mm(Point2(0, 0), ordered), 99 * 2.54 * 1.1);
  EXPECT_GT(travel_mm(Point2(0, 0), at), 3 * travel_mm(Point2(0, 0), ordered));
}

TEST(DrillOrder, HolesAreGroupedByDiameterSmallestFirst) {
  const std::vector<Point2> at = {{0, 0}, {10, 0}, {20, 0}, {30, 0}};
  const DrillPlan p = order_holes(at, {1.0, 0.8, 1.0, 0.8}, {2, 1, 2, 1}, Point2(0, 0));
  ASSERT_EQ(p.groups.size(), 2u);
  EXPECT_DOUBLE_EQ(p.groups[0].diameter_mm, 0.8);
  EXPECT_EQ(p.groups[0].tool, 1);
  EXPECT_EQ(p.groups[0].holes_mm.size(), 2u);
  EXPECT_DOUBLE_EQ(p.groups[1].diameter_mm, 1.0);
  EXPECT_EQ(p.groups[1].file_index.size(), 2u);
}

}  // namespace
}  // namespace host::pcb
