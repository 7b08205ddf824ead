// The height map and depth error pictures: written where asked, refused with the file's name.
#include "host/lib/plot/height_map_plot.h"

#include <gtest/gtest.h>

#include <cstdio>      // std::remove
#include <filesystem>  // file_size
#include <fstream>     // std::ifstream
#include <sstream>     // std::stringstream

namespace host {
namespace {

heightmap::HeightMap two_by_two() {
  heightmap::HeightMap m;
  m.rows = m.cols = 2;
  m.pitch_x_mm = 40;
  m.pitch_y_mm = 30;
  m.heights_um = {0, 100, 50, 150};
  return m;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(HeightMapPlot, WritesAnSvgOfTheMap) {
  const std::string path = (std::filesystem::temp_directory_path() / "hm_plot_test.svg").string();
  write_height_map_svg(two_by_two(), "blank", path);
  const std::string svg = read(path);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  // The 800 x 640 pt page, the interpolated field as one embedded image.
  EXPECT_NE(svg.find("width=\"800pt\""), std::string::npos);
  EXPECT_NE(svg.find("data:image/png;base64,"), std::string::npos);
  std::remove(path.c_str());
}

TEST(HeightMapPlot, DepthErrorPlotRefusesAPathItCannotWrite) {
  std::vector<heightmap::DepthSample> s = {{0, 0, -5, true}, {10, 0, 5, false}};
  try {
    write_depth_error_svg(s, 50, "board", "/nonexistent-dir/x.svg");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent-dir/x.svg: cannot write the plot", 0), 0u)
        << e.what();
  }
}

}  // namespace
}  // namespace host
