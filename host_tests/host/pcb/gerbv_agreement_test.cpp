// Each of the project's own Gerber and Excellon test files, read by our readers and by gerbv
// (the independent reference), rasterised over the same window at 2000 dpi (12.7 um
// pixels): they agree on more than 99.5 % of the pixels, and the pixels that differ are all
// at edges (gerbv snaps strokes to the pixel grid).
#include <gtest/gtest.h>

#include <cstdio>   // std::printf, std::remove
#include <cstdlib>  // std::abs
#include <fstream>  // std::ifstream

#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_reader.h"
#include "host_tests/host/pcb/raster_compare.h"
#include "host_tests/host/pcb/test_data.h"

namespace host::pcb {
namespace {

class GerbvAgreement : public ::testing::TestWithParam<const char*> {};

TEST_P(GerbvAgreement, CopperOrHolesMatchGerbvsImage) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  const std::string name = GetParam();
  const std::string path = test::data_file(name);
  const bool drill = name.size() > 4 && name.substr(name.size() - 4) == ".drl";
  const PcbLayer l = drill ? read_excellon_file(path) : read_gerber_file(path);
  const ClipperLib::Paths shapes = drill ? test::drill_shapes(l) : l.polygons_nm;
  ASSERT_FALSE(shapes.empty());
  // A negative image's copper is its bounding box with gerbv's 5 % border less what is drawn;
  // gerbv fills its whole picture: compared over that box alone.
  const bool negative = name == "image_negative.gbr";
  const test::Window win = test::window_around(l, negative ? 0.0 : 0.5, 2000);
  const test::Raster ours = test::rasterise(shapes, win);
  const test::Raster ref = test::gerbv_render(path, win);
  const test::Agreement a = test::compare(ours, ref);
  std::printf("%s: %.4f %% of %zu pixels agree, %.3f %% of copper; %zu differ away from edges\n",
              name.c_str(), 100 * a.of_all(), a.pixels, 100 * a.of_copper(), a.beyond_edge);
  EXPECT_GT(a.of_all(), 0.995);
  EXPECT_LE(a.beyond_edge, a.dark_either / 2000);
  if (a.beyond_edge > a.dark_either / 2000) {
    test::write_difference(ours, ref, "/tmp/engraver_pcb_diff_" + name + ".ppm");
  }
}

// gerbv's copper pixels with no copper of ours within one pixel (12.7 um at 2000 dpi).
size_t gerbv_copper_we_miss(const test::Raster& ours, const test::Raster& ref) {
  size_t missed = 0;
  for (int y = 0; y < ref.h; ++y) {
    for (int x = 0; x < ref.w; ++x) {
      if (!ref.dark[static_cast<size_t>(y) * ref.w + x]) continue;
      bool near = false;
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dx = -1; dx <= 1 && !near; ++dx) {
          const int u = x + dx, v = y + dy;
          near = u >= 0 && v >= 0 && u < ours.w && v < ours.h &&
                 ours.dark[static_cast<size_t>(v) * ours.w + u];
        }
      }
      missed += !near;
    }
  }
  return missed;
}

// Arcs 50.8 um off their circle (3-decimal inch, as Protel writes): every pixel gerbv draws
// as copper is copper in our reading too, so no tool path keeps clear of ours but cuts
// gerbv's (without both readings, 5 906 of gerbv's copper pixels lay outside ours).
TEST(GerbvIllDefinedArcs, GerbvsCopperIsInsideOurs) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  const std::string path = test::data_file("ill_defined_arcs.gbr");
  const PcbLayer l = read_gerber_file(path);
  const test::Window win = test::window_around(l, 0.5, 2000);
  const test::Raster ours = test::rasterise(l.polygons_nm, win);
  const test::Raster ref = test::gerbv_render(path, win);
  ASSERT_GT(ref.count(), 1000u);
  EXPECT_EQ(gerbv_copper_we_miss(ours, ref), 0u);
}

// Half circles of radius 0.5 mm drawn with a 0.25 mm square (not allowed by the spec; gerbv
// strokes them with square caps), compared at 10 000 dpi (2.54 um pixels): the ends were square to
// the last chord, not to the arc, and their corners stood 5 um out and in (256 px beyond an edge;
// now 0).
TEST(GerbvRectangleArcs, SquareEndsMatchGerbvsAt10000Dpi) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  const std::string path = testing::TempDir() + "/rectangle_arcs.gbr";
  std::ofstream(path) << "%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,0.25X0.25*%\nD10*\nG75*\n"
                         "X500000Y0D02*\nG03X-500000Y0I-500000J0D01*\n"
                         "X1600000Y0D02*\nG02X3600000Y0I1000000J0D01*\nM02*\n";
  const PcbLayer l = read_gerber_file(path);
  const test::Window win = test::window_around(l, 0.05, 10000);
  const test::Raster ours = test::rasterise(l.polygons_nm, win);
  const test::Raster ref = test::gerbv_render(path, win);
  ASSERT_GT(ref.count(), 100000u);
  const test::Agreement a = test::compare(ours, ref);
  std::printf("rectangle arcs: %zu of %zu copper px differ, %zu beyond an edge\n", a.mismatched,
              a.dark_either, a.beyond_edge);
  EXPECT_LE(a.beyond_edge, 8u);
  std::remove(path.c_str());
}

// gerbv sizes its picture as window inches x dpi in float, truncated: a window of 2021 px at
// 500 dpi (4.042 in) came out 2020 px wide and the comparison was refused (two Protel layers
// of gerbv's protel-pnp, "gerbv image is 2020 x 2375, expected 2021 x 2375").
TEST(GerbvRender, AWindowOfAnyWholeNumberOfPixels) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  const std::string path = testing::TempDir() + "/window_pixels.gbr";
  std::ofstream(path) << "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,1*%\nD10*\nX1000000Y1000000D03*\nM02*\n";
  test::Window win;
  win.pixel_mm = 25.4 / 500;
  win.w = 2021;
  win.h = 2375;
  const test::Raster ref = test::gerbv_render(path, win);
  EXPECT_EQ(ref.w, 2021);
  EXPECT_EQ(ref.h, 2375);
  EXPECT_GT(ref.count(), 0u);
  std::remove(path.c_str());
}

// gerbv draws a zero-width stroke (no copper) one pixel wide: the corpus compares with such
// strokes drawn so in our picture too (pcb-tools' zero-width board outlines and circles
// differed by every pixel of them).
TEST(GerbvRender, StrokesThinnerThanAPixelAreOnePixelWideAsGerbvDrawsThem) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  const std::string path = testing::TempDir() + "/hairlines.gbr";
  std::ofstream(path) << "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,1*%\n%ADD11C,0*%\nD10*\n"
                         "X0Y0D03*\nD11*\nX2000000Y0D02*\nX2000000Y3000000D01*\n"
                         "X5000000Y3000000D01*\nM02*\n";
  const PcbLayer copper = read_gerber_file(path);
  GerberOptions as_strokes;
  as_strokes.forced_kind = LayerKind::kOutline;
  const PcbLayer strokes = read_gerber_file(path, as_strokes);
  const test::Window win = test::window_around(strokes, 0.5, 2000);
  const test::Raster ref = test::gerbv_render(path, win);
  const test::Agreement bare = test::compare(test::rasterise(copper.polygons_nm, win), ref);
  EXPECT_GT(bare.beyond_edge, bare.dark_either / 2000);  // the lines are all gerbv's
  ClipperLib::Paths both = copper.polygons_nm;
  const ClipperLib::Paths hair = test::hairlines(strokes, win.pixel_mm);
  EXPECT_EQ(hair.size(), 1u);  // the zero-width line, not the 1 mm flash
  both.insert(both.end(), hair.begin(), hair.end());
  const test::Agreement drawn = test::compare(test::rasterise(both, win), ref);
  EXPECT_LE(drawn.beyond_edge, drawn.dark_either / 2000);
  std::remove(path.c_str());
}

INSTANTIATE_TEST_SUITE_P(OwnFiles, GerbvAgreement,
                         ::testing::Values("arcs_multi_quadrant.gbr", "arcs_single_quadrant.gbr",
                                           "macros.gbr", "polarity_clear.gbr", "step_repeat.gbr",
                                           "apertures.gbr", "deprecated_inch.gbr", "regions.gbr",
                                           "x2_attributes.gbr", "metric_lz.drl", "inch_tz.drl",
                                           "slots_decimal.drl", "inch_lz_format.drl",
                                           // Deprecated parameters applied as gerbv does.
                                           "image_offset.gbr", "layer_rotation.gbr", "knockout.gbr",
                                           "image_negative.gbr", "knockout_border.gbr",
                                           // The last definition of a D code for every use.
                                           "aperture_redefined.gbr"));

}  // namespace
}  // namespace host::pcb

namespace host::pcb {
namespace {

// gerbv's own reading of a drill file, written back by gerbv in one fixed format (INCH,TZ,
// 4 decimals) and read again: every hole and slot of ours has gerbv's within its rounding
// (0.00005 in = 1.27 um for positions, 0.0005 in for diameters, which gerbv writes with 3
// decimals).
void expect_same_drilling(const std::string& path) {
  SCOPED_TRACE(path);
  const PcbLayer ours = read_excellon_file(path);
  const std::string exported = test::gerbv_drill_export(path);
  const PcbLayer theirs = read_excellon_file(exported);
  std::remove(exported.c_str());
  ASSERT_EQ(ours.holes.size(), theirs.holes.size());
  ASSERT_EQ(ours.slots.size(), theirs.slots.size());
  const double kPos = 1270 + 2, kDia = 12700 + 2;  // nm
  std::vector<bool> used(theirs.holes.size(), false);
  for (const Hole& h : ours.holes) {
    bool found = false;
    for (size_t k = 0; k < theirs.holes.size() && !found; ++k) {
      const Hole& t = theirs.holes[k];
      if (used[k] || std::abs(static_cast<double>(t.at.x - h.at.x)) > kPos ||
          std::abs(static_cast<double>(t.at.y - h.at.y)) > kPos) {
        continue;
      }
      EXPECT_LE(std::abs(static_cast<double>(t.diameter_nm - h.diameter_nm)), kDia);
      used[k] = found = true;
    }
    EXPECT_TRUE(found) << "no gerbv hole at " << h.at.x << ", " << h.at.y << " nm";
  }
  for (size_t k = 0; k < ours.slots.size(); ++k) {
    const Slot& a = ours.slots[k];
    bool found = false;
    for (const Slot& b : theirs.slots) {
      found |= std::abs(static_cast<double>(a.from.x - b.from.x)) <= kPos &&
               std::abs(static_cast<double>(a.from.y - b.from.y)) <= kPos &&
               std::abs(static_cast<double>(a.to.x - b.to.x)) <= kPos &&
               std::abs(static_cast<double>(a.to.y - b.to.y)) <= kPos;
    }
    EXPECT_TRUE(found) << "no gerbv slot from " << a.from.x << ", " << a.from.y << " nm";
  }
}

TEST(GerbvDrillExport, OwnDrillFilesReadAsGerbvReadsThem) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  for (const char* f :
       {"metric_lz.drl", "inch_tz.drl", "slots_decimal.drl", "inch_lz_format.drl"}) {
    expect_same_drilling(test::data_file(f));
  }
}

TEST(GerbvDrillExport, SharedDrillFilesReadAsGerbvReadsThem) {
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  const std::string shared = std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/";
  const char* files[] = {"pcb/easy-sdr/Gerber_Drill_PTH.DRL",
                         "pcb/example_board/example_board-PTH.drl",
                         "pcb/multivibrator/multivibrator.drl", "kicad519_D1MiniGSR-PTH.drl"};
  if (!std::ifstream(shared + files[0])) GTEST_SKIP() << shared << " (shared samples) absent";
  for (const char* f : files) expect_same_drilling(shared + f);
}

}  // namespace
}  // namespace host::pcb
