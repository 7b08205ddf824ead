// Each of the project's own Gerber and Excellon test files, read by our readers and by gerbv
// (the independent reference), rasterised over the same window at 2000 dpi (12.7 um
// pixels): they agree on more than 99.5 % of the pixels, and the pixels that differ are all
// at edges (gerbv snaps strokes to the pixel grid).
#include <gtest/gtest.h>

#include <cstdio>  // std::printf

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
  const test::Window win = test::window_around(l, 0.5, 2000);
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

INSTANTIATE_TEST_SUITE_P(OwnFiles, GerbvAgreement,
                         ::testing::Values("arcs_multi_quadrant.gbr", "arcs_single_quadrant.gbr",
                                           "macros.gbr", "polarity_clear.gbr", "step_repeat.gbr",
                                           "apertures.gbr", "deprecated_inch.gbr", "regions.gbr",
                                           "x2_attributes.gbr", "metric_lz.drl", "inch_tz.drl",
                                           "slots_decimal.drl", "inch_lz_format.drl"));

}  // namespace
}  // namespace host::pcb
