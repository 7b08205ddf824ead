// A board plot's SVG needs no cairo: the process maps libcairo (and its pixman, fontconfig,
// freetype, X11...) only when a PNG is asked for. This binary links the plot alone, as the
// engraver does, not cairo.
#include <gtest/gtest.h>

#include <filesystem>  // temp_directory_path, file_size
#include <fstream>     // std::ifstream
#include <sstream>     // std::stringstream

#include "host/lib/plot/board_plot.h"
#include "host_tests/host/pcb/synthetic_board.h"

namespace host {
namespace {

bool cairo_mapped() {
  std::ifstream maps("/proc/self/maps");
  std::stringstream text;
  text << maps.rdbuf();
  return text.str().find("libcairo") != std::string::npos;
}

TEST(BoardPlotCairoLoad, TheSvgLeavesCairoUnloadedThePngLoadsIt) {
  pcb::PcbLayer top =
      pcb::test::copper_layer({pcb::test::rect(0, 0, 4, 4)}, pcb::LayerKind::kCopperTop);
  pcb::BoardLayers l;
  l.copper_top = &top;
  pcb::BoardOptions o;
  o.isolation.tool_width_mm = 0.4;
  const pcb::BoardJob job = pcb::plan_board(l, o);
  BoardPlotInput in;
  in.title = "test";
  in.job = &job;
  in.width_px = 400;
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string svg = (dir / "board_plot_cairo_load_test.svg").string();
  const std::string png = (dir / "board_plot_cairo_load_test.png").string();
  ASSERT_FALSE(cairo_mapped());
  write_board_plot(in, svg, "");
  EXPECT_GT(std::filesystem::file_size(svg), 0u);
  EXPECT_FALSE(cairo_mapped());
  write_board_plot(in, "", png);
  EXPECT_GT(std::filesystem::file_size(png), 0u);
  EXPECT_TRUE(cairo_mapped());
  std::filesystem::remove(svg);
  std::filesystem::remove(png);
}

}  // namespace
}  // namespace host
