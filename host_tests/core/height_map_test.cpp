// core::HeightMap against a double-precision bilinear reference (Eigen for the cell's
// corner matrix): exact at the grid points, within 1 um everywhere, the nearest edge value
// outside the grid, continuous along paths, never outside the map's lowest..highest.
#include "firmware/core/height_map.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>  // std::clamp
#include <cmath>      // std::floor, std::lround
#include <cstdlib>    // std::abs
#include <random>     // std::mt19937
#include <vector>     // std::vector

namespace {

struct Grid {
  int cols = 2, rows = 2;
  int32_t x0 = 0, y0 = 0;
  int pitch_x = 1000, pitch_y = 1000;
  std::vector<int16_t> h;  // row-major
};

// Bilinear in double, clamped to the grid (the nearest edge value outside).
double reference(const Grid& g, double x, double y) {
  const double u = std::clamp((x - g.x0) / g.pitch_x, 0.0, double(g.cols - 1));
  const double v = std::clamp((y - g.y0) / g.pitch_y, 0.0, double(g.rows - 1));
  const int i = std::min(int(std::floor(u)), g.cols - 2);
  const int j = std::min(int(std::floor(v)), g.rows - 2);
  const double fx = u - i, fy = v - j;
  Eigen::Matrix2d corners;
  corners << g.h[j * g.cols + i], g.h[j * g.cols + i + 1], g.h[(j + 1) * g.cols + i],
      g.h[(j + 1) * g.cols + i + 1];
  const Eigen::RowVector2d wy(1.0 - fy, fy);
  const Eigen::Vector2d wx(1.0 - fx, fx);
  return wy * corners * wx;
}

Grid random_grid(std::mt19937& rng) {
  Grid g;
  g.cols = std::uniform_int_distribution<int>(2, 16)(rng);
  g.rows = std::uniform_int_distribution<int>(2, 16)(rng);
  g.pitch_x = std::uniform_int_distribution<int>(1000, 65535)(rng);
  g.pitch_y = std::uniform_int_distribution<int>(1000, 65535)(rng);
  g.x0 = std::uniform_int_distribution<int32_t>(-20000, 20000)(rng);
  g.y0 = std::uniform_int_distribution<int32_t>(-20000, 20000)(rng);
  // A surface: tilt + bow + a bump + noise, scaled into -1000..1000.
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double tilt_x = u(rng), tilt_y = u(rng), bow = u(rng), noise = std::abs(u(rng));
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const double sx = double(c) / (g.cols - 1) - 0.5, sy = double(r) / (g.rows - 1) - 0.5;
      double z = 400 * (tilt_x * sx + tilt_y * sy) + 300 * bow * (sx * sx + sy * sy) +
                 200 * noise * u(rng);
      g.h.push_back(static_cast<int16_t>(std::clamp(std::lround(z), -1000L, 1000L)));
    }
  }
  return g;
}

core::HeightMap* load(const Grid& g) {
  static core::HeightMap map;  // 540 bytes; one at a time
  EXPECT_TRUE(map.begin(g.cols, g.rows, g.x0, g.y0, g.pitch_x, g.pitch_y));
  for (size_t i = 0; i < g.h.size(); ++i) EXPECT_TRUE(map.set(i, g.h[i]));
  map.complete();
  return &map;
}

TEST(HeightMap, InactiveMapOffsetsNothing) {
  core::HeightMap map;
  EXPECT_FALSE(map.active());
  EXPECT_EQ(0, map.offset_um(1234, 5678));
  ASSERT_TRUE(map.begin(2, 2, 0, 0, 1000, 1000));
  ASSERT_TRUE(map.set(0, 500));
  EXPECT_EQ(0, map.offset_um(0, 0)) << "not complete: still off";
  map.complete();
  EXPECT_EQ(500, map.offset_um(0, 0));
  map.clear();
  EXPECT_EQ(0, map.offset_um(0, 0));
}

TEST(HeightMap, RefusesGridsAndHeightsOutsideItsLimits) {
  core::HeightMap map;
  EXPECT_FALSE(map.begin(1, 4, 0, 0, 5000, 5000));
  EXPECT_FALSE(map.begin(17, 4, 0, 0, 5000, 5000));
  EXPECT_FALSE(map.begin(4, 4, 0, 0, 999, 5000));
  ASSERT_TRUE(map.begin(16, 16, 0, 0, 1000, 65535));
  EXPECT_TRUE(map.set(255, 1000));
  EXPECT_FALSE(map.set(256, 0));
  EXPECT_FALSE(map.set(0, 1001));
  EXPECT_FALSE(map.set(0, -1001));
}

TEST(HeightMap, ExactAtTheGridPointsAndWithinOneMicrometreOfDoubleBilinear) {
  std::mt19937 rng(25);
  double worst = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Grid g = random_grid(rng);
    core::HeightMap* map = load(g);
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c) {
        ASSERT_EQ(g.h[r * g.cols + c], map->offset_um(g.x0 + c * g.pitch_x, g.y0 + r * g.pitch_y))
            << "grid point " << c << "," << r;
      }
    }
    const double w = double(g.cols - 1) * g.pitch_x, hgt = double(g.rows - 1) * g.pitch_y;
    std::uniform_real_distribution<double> fx(-0.1, 1.1), fy(-0.1, 1.1);
    for (int k = 0; k < 400; ++k) {
      const int32_t x = g.x0 + static_cast<int32_t>(std::lround(fx(rng) * w));
      const int32_t y = g.y0 + static_cast<int32_t>(std::lround(fy(rng) * hgt));
      const double want = reference(g, x, y);
      const double err = std::abs(map->offset_um(x, y) - want);
      worst = std::max(worst, err);
      ASSERT_LE(err, 1.0) << "trial " << trial << " at " << x << "," << y << " want " << want;
    }
  }
  RecordProperty("worst_error_um", std::to_string(worst));
  EXPECT_GT(worst, 0.0);  // the rounding to whole micrometres shows somewhere
}

TEST(HeightMap, OutsideTheGridTheNearestEdgeValueNeverAnExtrapolation) {
  Grid g;
  g.cols = 3;
  g.rows = 2;
  g.pitch_x = 10000;
  g.pitch_y = 20000;
  g.h = {0, 100, 300, -50, 50, 250};
  core::HeightMap* map = load(g);
  EXPECT_EQ(0, map->offset_um(-50000, -50000));      // below the first corner
  EXPECT_EQ(300, map->offset_um(900000, -1));        // right of the last column, row 0
  EXPECT_EQ(250, map->offset_um(900000, 900000));    // beyond the far corner
  EXPECT_EQ(200, map->offset_um(15000, -70000));     // row 0 between columns 1 and 2
  EXPECT_EQ(150, map->offset_um(15000, 20000 + 1));  // the last row, same X
  EXPECT_EQ(-25, map->offset_um(-1, 10000));         // left edge, half-way up
}

// Property: whatever order the points come in (the cell cache), the same offsets; along a
// random path of short steps the offset moves by at most the surface's slope times the
// step, plus the rounding; never outside lowest..highest.
TEST(HeightMap, PathsGiveContinuousOffsetsInsideTheMapsRangeWhateverTheOrder) {
  std::mt19937 rng(2026);
  for (int trial = 0; trial < 100; ++trial) {
    const Grid g = random_grid(rng);
    core::HeightMap* map = load(g);
    const int16_t lo = *std::min_element(g.h.begin(), g.h.end());
    const int16_t hi = *std::max_element(g.h.begin(), g.h.end());
    EXPECT_EQ(lo, map->lowest_um());
    EXPECT_EQ(hi, map->highest_um());
    double max_slope = 0;  // um per um, over every cell edge
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c) {
        if (c + 1 < g.cols)
          max_slope = std::max(max_slope, std::abs(g.h[r * g.cols + c + 1] - g.h[r * g.cols + c]) /
                                              double(g.pitch_x));
        if (r + 1 < g.rows)
          max_slope =
              std::max(max_slope, std::abs(g.h[(r + 1) * g.cols + c] - g.h[r * g.cols + c]) /
                                      double(g.pitch_y));
      }
    }
    const double w = double(g.cols - 1) * g.pitch_x, hgt = double(g.rows - 1) * g.pitch_y;
    double x = g.x0 - 0.05 * w, y = g.y0 + 0.5 * hgt;
    std::uniform_real_distribution<double> turn(-0.3, 0.3);
    double heading = 0;
    std::vector<std::pair<int32_t, int32_t>> path;
    int16_t prev = map->offset_um(static_cast<int32_t>(x), static_cast<int32_t>(y));
    for (int k = 0; k < 3000; ++k) {
      heading += turn(rng);
      const double step = 1 + (k % 7) * 40;  // 1 .. 241 um
      x += step * std::cos(heading) * (w + hgt) / 100000.0 + step * 0.3;
      y += step * std::sin(heading);
      const int32_t xi = static_cast<int32_t>(x), yi = static_cast<int32_t>(y);
      const int16_t z = map->offset_um(xi, yi);
      ASSERT_GE(z, lo);
      ASSERT_LE(z, hi);
      if (!path.empty()) {
        const double d =
            std::hypot(double(xi - path.back().first), double(yi - path.back().second));
        ASSERT_LE(std::abs(z - prev), 2 * max_slope * d + 2) << "trial " << trial << " step " << k;
      }
      path.emplace_back(xi, yi);
      prev = z;
    }
    std::shuffle(path.begin(), path.end(), rng);
    for (const auto& p : path) {
      ASSERT_NEAR(reference(g, p.first, p.second), map->offset_um(p.first, p.second), 1.0);
    }
  }
}

}  // namespace
