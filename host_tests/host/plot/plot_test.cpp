// Plots: both files are written; the PNG has the asked size and ink where the curves and
// the tool path are (read back with cairo); the SVG is XML with the legend text.
#include "host/lib/plot/plot.h"

#include <cairo.h>
#include <expat.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "host/lib/drawing/conics.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/plot/plan_plot.h"
#include "host_tests/host/temp_dir.h"

namespace host {
namespace {

// A 100 x 50 mm rectangle drawn, a pen-up move down its left edge and a pen-down path along
// its bottom edge.
PlotInput rectangle_input() {
  PlotInput in;
  in.title = "rectangle test";
  in.width_px = 800;
  in.height_px = 600;
  in.drawing_curves_mm.push_back({{0, 0}, {100, 0}, {100, 50}, {0, 50}, {0, 0}});
  in.tool_path.add({0, 50}, false);
  in.tool_path.add({0, 0}, true);  // the pen-up piece ends where the cut begins
  in.tool_path.add({100, 0}, true);
  return in;
}

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// RGB of a pixel of an ARGB32 image.
struct Pixel {
  int r, g, b;
};
Pixel pixel(cairo_surface_t* s, int x, int y) {
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  const uint32_t v = *reinterpret_cast<const uint32_t*>(data + y * stride + x * 4);
  return Pixel{static_cast<int>((v >> 16) & 0xff), static_cast<int>((v >> 8) & 0xff),
               static_cast<int>(v & 0xff)};
}
bool is_white(const Pixel& p) {
  return p.r > 250 && p.g > 250 && p.b > 250;
}

// The plots go into a folder of their own, removed after each test.
class Plot : public testing::Test {
 protected:
  test::TempDir dir_{"plot_test_"};
  const std::string svg_ = dir_.file("plot.svg");
  const std::string png_ = dir_.file("plot.png");
};

// The fixture as a test sees it, set up and torn down by hand.
class PlotFixtureByHand : public Plot {
 public:
  void TestBody() override {}
  void set_up() { SetUp(); }
  void tear_down() { TearDown(); }
  using Plot::png_;
  using Plot::svg_;
};

// What a Plot test writes is gone after it (files named by pid alone were left in /tmp).
TEST(PlotFixture, RemovesWhatItsTestWrote) {
  std::string svg, png;
  {
    PlotFixtureByHand t;
    t.set_up();
    svg = t.svg_;
    png = t.png_;
    write_plot(rectangle_input(), svg, png);
    ASSERT_TRUE(std::filesystem::exists(svg));
    ASSERT_TRUE(std::filesystem::exists(png));
    t.tear_down();
  }
  EXPECT_FALSE(std::filesystem::exists(svg)) << svg;
  EXPECT_FALSE(std::filesystem::exists(png)) << png;
}

TEST_F(Plot, PngHasTheAskedSize) {
  write_plot(rectangle_input(), "", png_);
  cairo_surface_t* s = cairo_image_surface_create_from_png(png_.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(cairo_image_surface_get_width(s), 800);
  EXPECT_EQ(cairo_image_surface_get_height(s), 600);
  cairo_surface_destroy(s);
}

TEST_F(Plot, PngHasInkOnTheCurvesAndBackgroundInside) {
  const PlotInput in = rectangle_input();
  write_plot(in, "", png_);
  cairo_surface_t* s = cairo_image_surface_create_from_png(png_.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  const PlotFrame f = plot_frame(in);
  // Bottom edge: the red pen-down path over the drawing.
  const Point2 bottom = f.to_px({50, 0});
  const Pixel b = pixel(s, static_cast<int>(bottom.x()), static_cast<int>(bottom.y()));
  EXPECT_GT(b.r, b.g + 50) << b.r << " " << b.g << " " << b.b;  // red dominates
  // Right edge: the drawing only (light blue).
  const Point2 right = f.to_px({100, 25});
  const Pixel r = pixel(s, static_cast<int>(right.x()), static_cast<int>(right.y()));
  EXPECT_FALSE(is_white(r));
  EXPECT_GT(r.b, r.r);
  // Centre of the rectangle: background.
  const Point2 centre = f.to_px({50, 25});
  EXPECT_TRUE(is_white(pixel(s, static_cast<int>(centre.x()), static_cast<int>(centre.y()))));
  cairo_surface_destroy(s);
}

TEST_F(Plot, FrameKeepsTheAspectAndFitsInside) {
  const PlotInput in = rectangle_input();
  const PlotFrame f = plot_frame(in);
  const Point2 a = f.to_px({0, 0}), b = f.to_px({100, 50});
  EXPECT_NEAR((b.x() - a.x()) / (a.y() - b.y()), 2.0, 1e-9);  // y up in mm, down in px
  EXPECT_GE(a.x(), 0);
  EXPECT_LE(b.x(), 800);
  EXPECT_GE(b.y(), 40);        // below the title band
  EXPECT_LE(a.y(), 600 - 60);  // above the legend band
}

// What an XML parse of the SVG found: the root element and the text content.
struct SvgParse {
  std::string root;
  std::string text;
  int depth = 0;
};

SvgParse parse_svg(const std::string& svg, bool* well_formed) {
  SvgParse p;
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &p);
  XML_SetElementHandler(
      parser,
      [](void* u, const XML_Char* name, const XML_Char**) {
        SvgParse* q = static_cast<SvgParse*>(u);
        if (q->depth++ == 0) q->root = name;
      },
      [](void* u, const XML_Char*) { --static_cast<SvgParse*>(u)->depth; });
  XML_SetCharacterDataHandler(parser, [](void* u, const XML_Char* s, int len) {
    static_cast<SvgParse*>(u)->text.append(s, static_cast<size_t>(len));
  });
  *well_formed = XML_Parse(parser, svg.data(), static_cast<int>(svg.size()), 1) == XML_STATUS_OK;
  XML_ParserFree(parser);
  return p;
}

TEST_F(Plot, SvgParsesAsXmlAndHoldsTheTitleAndLegendText) {
  write_plot(rectangle_input(), svg_, "");
  bool ok = false;
  const SvgParse p = parse_svg(read_all(svg_), &ok);
  ASSERT_TRUE(ok);
  EXPECT_EQ(p.root, "svg");
  EXPECT_NE(p.text.find("rectangle test"), std::string::npos);
  EXPECT_NE(p.text.find("tool path (pen down)"), std::string::npos);
  EXPECT_NE(p.text.find("rapid (pen up)"), std::string::npos);
}

TEST_F(Plot, SvgDrawsPenUpMovesDashed) {
  write_plot(rectangle_input(), svg_, "");
  EXPECT_NE(read_all(svg_).find("stroke-dasharray"), std::string::npos);
}

TEST_F(Plot, SvgDrawsEachLayerInItsColourThroughThePlotFrame) {
  const PlotInput in = rectangle_input();
  write_plot(in, svg_, "");
  const std::string svg = read_all(svg_);
  // The drawing (light blue, 5 px), the pen-up move (grey, dashed), the cut (red), in order.
  const size_t drawing = svg.find("stroke=\"rgb(140,191,242)\" stroke-width=\"5\"");
  const size_t rapid = svg.find("stroke=\"rgb(115,115,115)\" stroke-width=\"0.8\"");
  const size_t cut = svg.find("stroke=\"rgb(191,13,13)\" stroke-width=\"1.2\"");
  ASSERT_NE(drawing, std::string::npos) << svg;
  ASSERT_NE(rapid, std::string::npos) << svg;
  ASSERT_NE(cut, std::string::npos) << svg;
  EXPECT_LT(drawing, rapid);
  EXPECT_LT(rapid, cut);
  // The drawing's rectangle at its pixels: (0, 0) mm first, (100, 50) mm third.
  const PlotFrame f = plot_frame(in);
  const Point2 a = f.to_px({0, 0}), c = f.to_px({100, 50});
  std::ostringstream corners;
  corners << "d=\"M" << a.x() << " " << a.y() << " L";
  EXPECT_NE(svg.find(corners.str(), drawing), std::string::npos) << corners.str() << "\n" << svg;
  std::ostringstream far;
  far << " " << c.x() << " " << c.y() << " ";
  EXPECT_NE(svg.find(far.str(), drawing), std::string::npos) << far.str();
  // Text as text: the title, and the scale bar's length.
  EXPECT_NE(svg.find(">rectangle test</text>"), std::string::npos);
  EXPECT_NE(svg.find(" mm</text>"), std::string::npos);
}

TEST_F(Plot, UnwritablePathIsReportedWithTheFileName) {
  try {
    write_plot(rectangle_input(), "", "/nonexistent/dir/p.png");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/p.png"), std::string::npos);
  }
}

TEST_F(Plot, PlanPlotHasOneDashedMovePerPenLiftPlusTheWayHome) {
  Drawing d;
  Curve c;
  c.set_spline(line_spline({0, 0}, {10, 0}));
  d.curves.push_back(c);
  c.set_spline(line_spline({0, 5}, {10, 5}));
  d.curves.push_back(c);
  const JobPlan p = plan_job(d, PlanOptions());
  const PlotInput in = plot_input_from_plan(p, "plan");
  int up = 0, down = 0;
  in.tool_path.each_piece([&](const std::vector<Point2>&, bool d) { (d ? down : up) += 1; });
  EXPECT_EQ(down, 2);
  EXPECT_EQ(up, 3);  // to the first curve, between the curves, home
  EXPECT_EQ(in.drawing_curves_mm.size(), 2u);
}

}  // namespace
}  // namespace host
