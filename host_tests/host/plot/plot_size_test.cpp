// Plots of big jobs stay small: detail below half a pixel is dropped, and a layer with more
// vertices than an SVG should hold becomes an image inside the SVG. The PNG keeps the ink.
#include <gtest/gtest.h>

#include <cmath>       // std::cos
#include <filesystem>  // file_size
#include <fstream>     // std::ifstream
#include <random>      // std::mt19937
#include <sstream>     // std::stringstream

#include "host/lib/plot/plot.h"
#include "host_tests/host/temp_dir.h"

namespace host {
namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class PlotSize : public ::testing::Test {
 protected:
  test::TempDir dir_{"engraver_plot_size_"};  // removed after each test
  const std::string svg_ = dir_.file("plot.svg");
  const std::string png_ = dir_.file("plot.png");
};

TEST_F(PlotSize, DenseLongPathIsThinnedToThePixelGrid) {
  // A 60 mm circle traced with a million points (0.0002 mm apart): what a 1 000-pixel plot
  // can show is about the circle's 560-pixel circumference, not a million vertices.
  PlotInput in;
  in.title = "dense";
  for (int i = 0; i <= 1000000; ++i) {
    const double a = 2 * M_PI * i / 1000000;
    in.tool_path.add(Point2(30 + 30 * std::cos(a), 30 + 30 * std::sin(a)), true);
  }
  in.drawing_curves_mm.push_back({{0, 0}, {60, 60}});
  write_plot(in, svg_, png_);
  const std::string svg = read_all(svg_);
  EXPECT_LT(svg.size(), 200000u);                    // a million vertices as text would be ~20 MB
  EXPECT_EQ(svg.find("<image"), std::string::npos);  // still vectors
}

TEST_F(PlotSize, HugeLayerBecomesAnImageAndTheSvgStaysSmall) {
  // 400 000 scattered short strokes: more vertices than an SVG layer may hold.
  PlotInput in;
  in.title = "many strokes";
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 280), d(-2, 2);
  for (int i = 0; i < 400000; ++i) {
    const Point2 a(u(rng), u(rng) * 0.7);
    in.drawing_curves_mm.push_back({a, a + Point2(d(rng), d(rng))});
  }
  write_plot(in, svg_, png_);
  const std::string svg = read_all(svg_);
  EXPECT_NE(svg.find("<image"), std::string::npos);
  EXPECT_LT(svg.size(), 5u * 1024 * 1024);
  EXPECT_NE(svg.find("<title>many strokes</title>"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(png_), 10000u);  // the PNG has the ink
}

}  // namespace
}  // namespace host
