// The board plot shows what matters where it is: copper, the tool's swept width, holes.
#include "host/lib/plot/board_plot.h"

#include <cairo.h>  // read the PNG back
#include <gtest/gtest.h>
#include <sys/resource.h>  // getrusage
#include <sys/wait.h>      // waitpid
#include <unistd.h>        // fork

#include <cmath>       // std::round
#include <cstdio>      // std::snprintf
#include <filesystem>  // temp_directory_path
#include <fstream>     // std::ifstream
#include <sstream>     // std::stringstream

#include "host_tests/host/pcb/synthetic_board.h"

namespace host {
namespace {

struct Pixel {
  int r, g, b;
};

Pixel pixel_at(cairo_surface_t* s, const Point2& px) {
  const unsigned char* d = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  const int x = static_cast<int>(px.x()), y = static_cast<int>(px.y());
  const uint32_t v = *reinterpret_cast<const uint32_t*>(d + y * stride + 4 * x);
  return Pixel{static_cast<int>((v >> 16) & 255), static_cast<int>((v >> 8) & 255),
               static_cast<int>(v & 255)};
}

// A 4 mm copper square with a 1 mm hole at its centre, isolated with a 0.4 mm tool.
pcb::BoardJob square_with_a_hole() {
  pcb::PcbLayer top =
      pcb::test::copper_layer({pcb::test::rect(0, 0, 4, 4)}, pcb::LayerKind::kCopperTop);
  pcb::PcbLayer drill;
  drill.path = "t.drl";
  drill.holes = {pcb::test::hole(2, 2, 1.0, 1)};
  pcb::BoardLayers l;
  l.copper_top = &top;
  l.drill = &drill;
  pcb::BoardOptions o;
  o.isolation.tool_width_mm = 0.4;
  return pcb::plan_board(l, o);
}

// A file of this test process in the temporary folder (worktrees run these tests at once).
std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-" + name))
      .string();
}

TEST(BoardPlot, CopperIsolationAndHolesAppearWhereTheyAre) {
  const pcb::BoardJob job = square_with_a_hole();
  BoardPlotInput in;
  in.title = "test";
  in.job = &job;
  in.width_px = 800;
  const std::string png = temp_file("pcb_board_plot_test.png");
  write_board_plot(in, "", png);
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  int h = 0;
  const PlotFrame f = board_plot_frame(job, 800, &h);
  EXPECT_EQ(cairo_image_surface_get_height(s), h);
  // Hole centre: dark. Copper between hole and edge: copper orange. Just outside the copper,
  // inside the tool's width: blue dominates.
  const Pixel hole = pixel_at(s, f.to_px(job.frame.to_machine(Point2(2, 2))));
  EXPECT_LT(hole.r + hole.g + hole.b, 120);
  const Pixel copper = pixel_at(s, f.to_px(job.frame.to_machine(Point2(3.2, 3.2))));
  EXPECT_GT(copper.r, 180);
  EXPECT_LT(copper.b, 100);
  const Pixel cut = pixel_at(s, f.to_px(job.frame.to_machine(Point2(4.1, 2.7))));
  EXPECT_GT(cut.b, cut.r + 40);
  const Pixel outside = pixel_at(s, f.to_px(job.frame.to_machine(Point2(4.8, 2.7))));
  EXPECT_EQ(outside.r + outside.g + outside.b, 3 * 255);
  cairo_surface_destroy(s);
  std::filesystem::remove(png);
}

// The SVG is written as text (no cairo, no fontconfig at start-up): the same picture's
// parts at the same places, its legend as text a reader can search.
TEST(BoardPlot, SvgIsPlainTextWithTheLegendAndTheHoleWhereItIs) {
  const pcb::BoardJob job = square_with_a_hole();
  BoardPlotInput in;
  in.title = "a <test> & more";
  in.job = &job;
  in.width_px = 800;
  const std::string svg_path = temp_file("pcb_board_plot_test.svg");
  write_board_plot(in, svg_path, "");
  std::ifstream file(svg_path);
  std::stringstream text;
  text << file.rdbuf();
  const std::string svg = text.str();
  std::filesystem::remove(svg_path);
  int h = 0;
  const PlotFrame f = board_plot_frame(job, 800, &h);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("width=\"800pt\" height=\"" + std::to_string(h) + "pt\""), std::string::npos);
  EXPECT_NE(svg.find(">a &lt;test&gt; &amp; more</text>"), std::string::npos);
  EXPECT_NE(svg.find(">isolation (tool width)</text>"), std::string::npos);
  EXPECT_NE(svg.find("<path fill=\"rgb(217,140,51)\" fill-rule=\"evenodd\" d=\"M"),
            std::string::npos);  // the copper
  EXPECT_NE(svg.find("<g opacity=\"0.45\" fill=\"none\" stroke=\"rgb(38,89,230)\""),
            std::string::npos);  // the tool's swept width
  const Point2 hole = f.to_px(job.frame.to_machine(Point2(2, 2)));
  char circle[96];
  std::snprintf(circle, sizeof circle, "<circle cx=\"%g\" cy=\"%g\" r=\"%g\"/>",
                std::round(hole.x() * 100) / 100, std::round(hole.y() * 100) / 100,
                std::round(0.5 * f.scale_px_per_mm * 100) / 100);
  EXPECT_NE(svg.find(circle), std::string::npos) << circle;
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

// The PNG is drawn a band of rows at a time: a plot of 6 000 x 6 000 pixels (140 MB as one
// cairo surface, twice that with a stroke group) is written in a few MB, and is whole.
TEST(BoardPlot, ALargePngIsWrittenInBandsOfRows) {
  pcb::PcbLayer top =
      pcb::test::copper_layer({pcb::test::rect(0, 0, 40, 40)}, pcb::LayerKind::kCopperTop);
  pcb::BoardLayers l;
  l.copper_top = &top;
  pcb::BoardOptions o;
  o.isolation.tool_width_mm = 0.4;
  const pcb::BoardJob job = pcb::plan_board(l, o);
  BoardPlotInput in;
  in.title = "large";
  in.job = &job;
  in.width_px = 6000;
  const std::string png = temp_file("pcb_board_plot_large_test.png");
  // In a child process, so that its peak resident memory counts this plot alone.
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    write_board_plot(in, "", png);
    getrusage(RUSAGE_SELF, &after);
    _exit(after.ru_maxrss - before.ru_maxrss < 32 * 1024 ? 0 : 1);  // kB
  }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "the plot's peak memory grew by 32 MB or more";
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  int h = 0;
  const PlotFrame f = board_plot_frame(job, 6000, &h);
  EXPECT_EQ(cairo_image_surface_get_height(s), h);
  // Copper and the tool's width on every band: along a line down the middle of the board.
  for (double y = 1; y < 39.5; y += 0.5) {
    const Pixel copper = pixel_at(s, f.to_px(job.frame.to_machine(Point2(20, y))));
    EXPECT_GT(copper.r, 180) << y;
    EXPECT_LT(copper.b, 100) << y;
    const Pixel cut = pixel_at(s, f.to_px(job.frame.to_machine(Point2(40.1, y))));
    EXPECT_GT(cut.b, cut.r + 40) << y;
  }
  cairo_surface_destroy(s);
  std::filesystem::remove(png);
}

}  // namespace
}  // namespace host
