// The probe grid: its size, its order, and the points its neighbours disagree with.
#include "host/lib/heightmap/probe_grid.h"

#include <gtest/gtest.h>

#include <set>  // std::set

namespace host::heightmap {
namespace {

TEST(ProbeGrid, SpacingGivesTheFewestPointsThatKeepEveryPitchWithinIt) {
  GridOptions o;
  o.spacing_mm = 10;
  o.margin_mm = 1;
  const ProbeGrid g = plan_probe_grid(AreaMm{5, 5, 63, 35}, o);  // 60 x 32 mm with the margin
  EXPECT_EQ(g.cols, 7);                                          // 6 gaps of 10 mm
  EXPECT_EQ(g.rows, 5);                                          // 4 gaps of 8 mm
  EXPECT_DOUBLE_EQ(g.origin_x_mm, 4);
  EXPECT_DOUBLE_EQ(g.origin_y_mm, 4);
  EXPECT_DOUBLE_EQ(g.pitch_x_mm, 10);
  EXPECT_DOUBLE_EQ(g.pitch_y_mm, 8);
  EXPECT_DOUBLE_EQ(g.x_mm(g.cols - 1), 64);
  EXPECT_DOUBLE_EQ(g.y_mm(g.rows - 1), 36);
}

TEST(ProbeGrid, TheMarginStopsAtTheZeroCorner) {
  GridOptions o;
  o.spacing_mm = 10;
  o.margin_mm = 1;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0.5, 40, 20}, o);  // a drawing at the corner
  EXPECT_DOUBLE_EQ(g.origin_x_mm, 0);
  EXPECT_DOUBLE_EQ(g.origin_y_mm, 0);
  EXPECT_DOUBLE_EQ(g.x_mm(g.cols - 1), 41);
  EXPECT_DOUBLE_EQ(g.y_mm(g.rows - 1), 21);
  const ProbeGrid below = plan_probe_grid(AreaMm{-5, -5, 40, 20}, o);  // a job past it
  EXPECT_DOUBLE_EQ(below.origin_x_mm, -6);
}

TEST(ProbeGrid, RowsAndColsAreTakenAsGiven) {
  GridOptions o;
  o.rows = 3;
  o.cols = 4;
  o.margin_mm = 0;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 30, 10}, o);
  EXPECT_EQ(g.rows, 3);
  EXPECT_EQ(g.cols, 4);
  EXPECT_DOUBLE_EQ(g.pitch_x_mm, 10);
  EXPECT_DOUBLE_EQ(g.pitch_y_mm, 5);
}

TEST(ProbeGrid, RefusesMorePointsThanTheControllerKeeps) {
  GridOptions o;
  o.spacing_mm = 5;
  try {
    plan_probe_grid(AreaMm{0, 0, 100, 20}, o);  // 101 mm (from X 0) / 5 -> 22 points
    FAIL();
  } catch (const GridError& e) {
    EXPECT_NE(std::string(e.what()).find("use a spacing of 6.7 mm or more"), std::string::npos)
        << e.what();
  }
  o.spacing_mm = 0;
  o.rows = 17;
  o.cols = 4;
  EXPECT_THROW(plan_probe_grid(AreaMm{0, 0, 100, 20}, o), GridError);
  o.rows = 1;
  EXPECT_THROW(plan_probe_grid(AreaMm{0, 0, 100, 20}, o), GridError);
}

TEST(ProbeGrid, RefusesAPitchTheControllerCannotTake) {
  GridOptions o;
  o.rows = 2;
  o.cols = 2;
  o.margin_mm = 0;
  EXPECT_THROW(plan_probe_grid(AreaMm{0, 0, 100, 20}, o), GridError);  // 100 mm pitch
  o.rows = o.cols = 16;
  EXPECT_THROW(plan_probe_grid(AreaMm{0, 0, 10, 10}, o), GridError);  // 0.67 mm pitch
  o.rows = o.cols = 0;
  o.spacing_mm = 70;
  EXPECT_THROW(plan_probe_grid(AreaMm{0, 0, 100, 20}, o), GridError);
}

TEST(ProbeOrder, ASerpentineVisitsEveryPointOnceWithOnlyNeighbourSteps) {
  GridOptions o;
  o.rows = 4;
  o.cols = 6;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 50, 30}, o);
  const std::vector<GridPoint> order = probe_order(g);
  ASSERT_EQ(order.size(), 24u);
  std::set<std::pair<int, int>> seen;
  for (size_t i = 0; i < order.size(); ++i) {
    seen.insert({order[i].row, order[i].col});
    if (i > 0)  // one grid step each time: 23 steps, the fewest that visit 24 points
      EXPECT_EQ(
          std::abs(order[i].row - order[i - 1].row) + std::abs(order[i].col - order[i - 1].col), 1);
  }
  EXPECT_EQ(seen.size(), 24u);
  EXPECT_EQ(order.front().row, 0);
  EXPECT_EQ(order.front().col, 0);
}

TEST(ProbeOrder, RunsAlongTheDirectionThatMakesTheShorterPath) {
  GridOptions o;
  o.rows = 5;
  o.cols = 5;
  o.margin_mm = 0;
  // Wide: pitch X 25 mm, Y 5 mm. Along rows: 5*4*25 + 4*5 = 520 mm; along columns 5*4*5 +
  // 4*25 = 200 mm.
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 100, 20}, o);
  const std::vector<GridPoint> order = probe_order(g);
  EXPECT_DOUBLE_EQ(travel_mm(g, order), 200.0);
  EXPECT_EQ(order[1].row, 1);  // up the first column
}

// A tilted, bowed blank sampled on a grid, with one point off by `error_um`.
std::vector<double> bowed(const ProbeGrid& g, int bad_row, int bad_col, double error_um) {
  std::vector<double> h;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const double u = (g.x_mm(c) - 50) / 50, v = (g.y_mm(r) - 40) / 40;
      double z = g.x_mm(c) + 200 * (1 - 0.5 * (u * u + v * v));
      if (r == bad_row && c == bad_col) z += error_um;
      h.push_back(z);
    }
  return h;
}

TEST(Outliers, NoneOnASmoothBlank) {
  GridOptions o;
  o.rows = 9;
  o.cols = 11;
  o.margin_mm = 0;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 100, 80}, o);
  EXPECT_TRUE(find_outliers(g, bowed(g, -1, -1, 0), 25).empty());
}

TEST(Outliers, NoneOnAStronglyBowedNarrowBlank) {
  // engraver-word's 126 x 32 mm with a 0.2 mm bow over it: 0.9 um/mm^2 across its rows 8 mm
  // apart, which straight-line extrapolation from two rows missed by 57 um.
  GridOptions o;
  o.spacing_mm = 10;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 124, 30}, o);
  ASSERT_EQ(g.rows, 5);
  std::vector<double> h;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const double u = (g.x_mm(c) - 62) / 62, v = (g.y_mm(r) - 15) / 15;
      h.push_back(100 * g.x_mm(c) / 124 + 200 * (1 - 0.5 * (u * u + v * v)));
    }
  EXPECT_TRUE(find_outliers(g, h, 25).empty());
}

TEST(Outliers, OneBadPointIsFoundAloneWhereverItIs) {
  GridOptions o;
  o.rows = 9;
  o.cols = 11;
  o.margin_mm = 0;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 100, 80}, o);
  for (const GridPoint p : {GridPoint{4, 5}, GridPoint{0, 0}, GridPoint{8, 3}, GridPoint{1, 10}}) {
    for (const double error : {-60.0, 40.0}) {
      const std::vector<Outlier> found = find_outliers(g, bowed(g, p.row, p.col, error), 25);
      ASSERT_EQ(found.size(), 1u) << p.row << "," << p.col << " " << error;
      EXPECT_EQ(found[0].point.row, p.row);
      EXPECT_EQ(found[0].point.col, p.col);
      // The neighbours' quadratics predict a tilt and a bow exactly.
      EXPECT_NEAR(found[0].height_um - found[0].predicted_um, error, 1e-6);
    }
  }
}

TEST(Outliers, DescribedWithTheirPlace) {
  GridOptions o;
  o.rows = 3;
  o.cols = 3;
  o.margin_mm = 0;
  const ProbeGrid g = plan_probe_grid(AreaMm{0, 0, 20, 10}, o);
  std::vector<double> h(9, 0.0);
  h[4] = 50;
  const std::vector<Outlier> found = find_outliers(g, h, 25);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(describe_outlier(g, found[0]),
            "row 1, col 1 at (10.000, 5.000) mm reads 50.0 um, its neighbours 0.0 um");
}

}  // namespace
}  // namespace host::heightmap
