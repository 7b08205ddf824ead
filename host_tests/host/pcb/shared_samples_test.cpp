// Every PCB file in ../shared/samples (real boards from KiCad 4/5, EasyEDA, Eagle via gerbv)
// reads without error, lands where the file puts it, and agrees with gerbv's rendering.
// Skips cleanly where ../shared is absent; the files are never copied into the repository.
#include <gtest/gtest.h>

#include <filesystem>  // std::filesystem

#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_reader.h"
#include "host/lib/pcb/pcb_file_names.h"
#include "host_tests/host/pcb/raster_compare.h"

namespace host::pcb {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = fs::path(ENGRAVER_SOURCE_DIR) / ".." / "shared" / "samples";

std::vector<fs::path> shared_pcb_files() {
  std::vector<fs::path> out;
  if (!fs::is_directory(kShared)) return out;
  for (const auto& e : fs::recursive_directory_iterator(kShared / "pcb")) {
    if (e.is_regular_file() && pcb_file_format(e.path().string()) != PcbFileFormat::kNone) {
      out.push_back(e.path());
    }
  }
  for (const auto& e : fs::directory_iterator(kShared)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".gbr" || ext == ".drl") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

PcbLayer read_any(const fs::path& p) {
  return pcb_file_format(p.string()) == PcbFileFormat::kExcellon ? read_excellon_file(p.string())
                                                                 : read_gerber_file(p.string());
}

#define REQUIRE_SHARED()                                                       \
  if (shared_pcb_files().empty()) {                                            \
    GTEST_SKIP() << kShared.string() << " (the team's shared samples) absent"; \
  }

TEST(SharedPcbSamples, EveryFileReadsWithoutError) {
  REQUIRE_SHARED();
  const std::vector<fs::path> files = shared_pcb_files();
  EXPECT_GE(files.size(), 14u);
  for (const fs::path& p : files) {
    SCOPED_TRACE(p.string());
    PcbLayer l;
    ASSERT_NO_THROW(l = read_any(p));
    if (l.kind == LayerKind::kDrill) {
      EXPECT_FALSE(l.holes.empty());
    } else {
      EXPECT_FALSE(l.polygons_nm.empty());
    }
  }
}

TEST(SharedPcbSamples, LayerKindsFromX2AttributesAndNames) {
  REQUIRE_SHARED();
  const fs::path b = kShared / "pcb";
  EXPECT_EQ(read_gerber_file((b / "example_board/example_board-F.Cu.gbr").string()).kind,
            LayerKind::kCopperTop);  // X2 in G04 #@! comments
  EXPECT_EQ(read_gerber_file((b / "multivibrator/multivibrator-B.Cu.gbr").string()).kind,
            LayerKind::kCopperBottom);  // %TF.FileFunction,Copper,L2,Bot,Signal*%
  EXPECT_EQ(read_gerber_file((b / "easy-sdr/Gerber_TopLayer.GTL").string()).kind,
            LayerKind::kCopperTop);  // extension
  EXPECT_EQ(read_gerber_file((b / "easy-sdr/Gerber_BoardOutline.GKO").string()).kind,
            LayerKind::kOutline);
  GerberOptions bottom;
  bottom.kind_if_unknown = LayerKind::kCopperBottom;
  EXPECT_EQ(read_gerber_file((b / "eaglecad1/top-cop.gbx").string(), bottom).kind,
            LayerKind::kCopperBottom);  // neither X2 nor a known name: the caller's choice
}

TEST(SharedPcbSamples, InchDrillFileLinesUpWithMillimetreGerbers) {
  REQUIRE_SHARED();
  const fs::path b = kShared / "pcb/example_board";
  const PcbLayer drill = read_excellon_file((b / "example_board-PTH.drl").string());
  ASSERT_EQ(drill.holes.size(), 3u);
  EXPECT_EQ(drill.units, "inch");
  // X0.9Y-0.45 inch, tool 0.0157 inch.
  EXPECT_EQ(drill.holes[0].at.x, 22860000);
  EXPECT_EQ(drill.holes[0].at.y, -11430000);
  EXPECT_EQ(drill.holes[0].diameter_nm, 398780);
  // Every hole sits inside copper of the mm top layer (its pads).
  const PcbLayer top = read_gerber_file((b / "example_board-F.Cu.gbr").string());
  for (const Hole& h : drill.holes) {
    int inside = 0;
    for (const auto& poly : top.polygons_nm) {
      const int r = ClipperLib::PointInPolygon({h.at.x, h.at.y}, poly);
      if (r != 0) inside += ClipperLib::Orientation(poly) ? 1 : -1;
    }
    EXPECT_EQ(inside, 1) << "hole at " << h.at.x << ", " << h.at.y << " nm";
  }
}

TEST(SharedPcbSamples, OutlinesAreClosedLoops) {
  REQUIRE_SHARED();
  for (const char* f :
       {"easy-sdr/Gerber_BoardOutline.GKO", "example_board/example_board-Edge.Cuts.gbr",
        "multivibrator/multivibrator-Edge.Cuts.gbr"}) {
    SCOPED_TRACE(f);
    const PcbLayer l = read_gerber_file((kShared / "pcb" / f).string());
    ASSERT_TRUE(l.outline_paths_are_open);
    ASSERT_EQ(l.polygons_nm.size(), 1u);
    EXPECT_TRUE(l.polygons_nm[0].front() == l.polygons_nm[0].back());
  }
}

// gerbv is the reference: our copper (or holes) against gerbv's PNG of the same file.
TEST(SharedPcbSamples, CopperAndHolesAgreeWithGerbv) {
  REQUIRE_SHARED();
  if (!test::gerbv_available()) GTEST_SKIP() << "gerbv not installed";
  for (const fs::path& p : shared_pcb_files()) {
    SCOPED_TRACE(p.string());
    const PcbLayer l = read_any(p);
    if (l.kind == LayerKind::kOutline) continue;  // centre lines, not areas
    const ClipperLib::Paths shapes =
        l.kind == LayerKind::kDrill ? test::drill_shapes(l) : l.polygons_nm;
    const test::Window win = test::window_around(l, 0.5, 1000);
    const test::Raster ours = test::rasterise(shapes, win);
    const test::Raster ref = test::gerbv_render(p.string(), win);
    const test::Agreement a = test::compare(ours, ref);
    // Stated agreement: > 99.5 % of all pixels of the window; and the pixels that differ are
    // edge pixels (gerbv snaps strokes to the pixel grid): at most 0.05 % of the copper
    // pixels differ with no like pixel beside them, so no pad, track or clearance of a few
    // pixels (25 um each at 1000 dpi) is missing or extra on either side.
    EXPECT_GT(a.of_all(), 0.995) << a.mismatched << " of " << a.pixels << " pixels differ";
    EXPECT_LE(a.beyond_edge, a.dark_either / 2000)
        << a.beyond_edge << " pixels differ away from any edge (" << a.mismatched << " of "
        << a.dark_either << " copper pixels differ in all)";
    std::printf(
        "%s: %.4f %% of %zu pixels agree, %.3f %% of copper pixels; %zu differ away from edges\n",
        p.filename().c_str(), 100 * a.of_all(), a.pixels, 100 * a.of_copper(), a.beyond_edge);
    if (a.beyond_edge > a.dark_either / 2000) {
      test::write_difference(ours, ref, "/tmp/engraver_pcb_diff_" + p.filename().string() + ".ppm");
    }
  }
}

}  // namespace
}  // namespace host::pcb
