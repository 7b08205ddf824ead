// `engraver info` and `engraver points` as functions: a Gerber file's and a drawing's
// reports, the firmware's points of a curve and the refused tolerances.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>  // temp_directory_path
#include <fstream>     // std::ofstream

#include "host/lib/commands/exit_codes.h"
#include "host/lib/commands/info_command.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host::commands {
namespace {

namespace fs = std::filesystem;

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path p =
      fs::temp_directory_path() / ("info_command_test-" + std::to_string(getpid()) + "-" + name);
  std::ofstream(p) << text;
  return p.string();
}

// Under %IR90 the tester read "y -0.250 .. 10.250 mm" and a height of 10.499 mm: the size
// came from the unrounded box (a round flash's polygon stops 0.3 um short of its radius),
// the ends were rounded. Every quarter turn: the ends the turned ones, the size their difference.
TEST(InfoCommand, ExtentsAndSizeAddUpUnderEveryImageRotation) {
  const std::string expected[] = {
      "extents:   x -0.250 .. 10.250 mm, y -0.250 .. 0.250 mm (10.500 x 0.500 mm)\n",
      "extents:   x -0.250 .. 0.250 mm, y -0.250 .. 10.250 mm (0.500 x 10.500 mm)\n",
      "extents:   x -10.250 .. 0.250 mm, y -0.250 .. 0.250 mm (10.500 x 0.500 mm)\n",
      "extents:   x -0.250 .. 0.250 mm, y -10.250 .. 0.250 mm (0.500 x 10.500 mm)\n",
  };
  for (int quarter = 0; quarter < 4; ++quarter) {
    const std::string ir = std::to_string(90 * quarter);
    const std::string path = write_file(
        "ir" + ir + ".gbr", "%FSLAX46Y46*%\n%MOMM*%\n%IR" + ir +
                                "*%\n%ADD10C,0.500000*%\nD10*\nX0Y0D03*\nX10000000Y0D03*\nM02*\n");
    const std::optional<PcbFileInfo> info = read_pcb_file_info(path);
    ASSERT_TRUE(info.has_value());
    const std::string text = pcb_info_text(*info);
    EXPECT_NE(text.find(expected[quarter]), std::string::npos) << "%IR" << ir << "\n" << text;
    fs::remove(path);
  }
}

TEST(InfoCommand, AGerberFilesLayerExtentsAndPolygons) {
  const std::string path = write_file(
      "pads-F.Cu.gbr",
      "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n%ADD10R,2.000000X2.000000*%\n"
      "D10*\nX10000000Y10000000D03*\nX20000000Y10000000D03*\nM02*\n");
  const std::optional<PcbFileInfo> info = read_pcb_file_info(path);
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->format, "Gerber RS-274X");
  const nlohmann::json j = pcb_info_json(*info);
  EXPECT_EQ(j["layer"], pcb::layer_kind_name(pcb::LayerKind::kCopperTop));
  EXPECT_EQ(j["polygons"], 2);
  EXPECT_DOUBLE_EQ(j["extents_mm"]["min"][0].get<double>(), 9.0);
  EXPECT_DOUBLE_EQ(j["extents_mm"]["max"][0].get<double>(), 21.0);
  const std::string text = pcb_info_text(*info);
  EXPECT_NE(text.find("extents:   x 9.000 .. 21.000 mm, y 9.000 .. 11.000 mm"), std::string::npos)
      << text;
  EXPECT_NE(text.find("polygons:  2 copper areas"), std::string::npos) << text;
}

// An inch drill file's sizes in the JSON at the text's resolution (um): 0.8, not 0.8001 or
// 0.7999999999999999.
TEST(InfoCommand, JsonSizesAreRoundedToTheMicrometreAsTheText) {
  const std::string path = write_file(
      "inch.drl",
      "M48\nINCH\nT1C0.0315\n%\nG90\nG05\nT1\nX0.393701Y0.393701\nX0.787402Y0.393701\nM30\n");
  const std::optional<PcbFileInfo> info = read_pcb_file_info(path);
  ASSERT_TRUE(info.has_value());
  const nlohmann::json j = pcb_info_json(*info);
  EXPECT_EQ(j["tools"]["T1"]["diameter_mm"].get<double>(), 0.8) << j.dump();
  EXPECT_EQ(j["extents_mm"]["min"][0].get<double>(), 9.6) << j.dump();
  EXPECT_EQ(j["extents_mm"]["max"][0].get<double>(), 20.4) << j.dump();
  EXPECT_EQ(j["extents_mm"]["width"].get<double>(), 10.8) << j.dump();
  EXPECT_EQ(j["extents_mm"]["height"].get<double>(), 0.8) << j.dump();
  const std::string text = pcb_info_text(*info);
  EXPECT_NE(text.find("x 9.600 .. 20.400 mm, y 9.600 .. 10.400 mm (10.800 x 0.800 mm)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("T1: 0.800 mm"), std::string::npos) << text;
  fs::remove(path);
}

// open_paths is a count (the guide's word): an outline's centre lines that do not close.
TEST(InfoCommand, OpenPathsCountsTheOutlinesOpenCentreLines) {
  const std::string path =
      write_file("edge-Edge.Cuts.gbr",
                 "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Profile,NP*%\n%ADD10C,0.100000*%\nD10*\n"
                 "X0Y0D02*\nX35000000Y0D01*\nX35000000Y25000000D01*\nX0Y25000000D01*\nX0Y0D01*\n"
                 "X5000000Y5000000D02*\nX10000000Y5000000D01*\nM02*\n");
  const std::optional<PcbFileInfo> info = read_pcb_file_info(path);
  ASSERT_TRUE(info.has_value());
  const nlohmann::json j = pcb_info_json(*info);
  EXPECT_EQ(j["open_paths"], 1) << j.dump();
  EXPECT_NE(pcb_info_text(*info).find("paths:     2 centre lines (1 closed)"), std::string::npos)
      << pcb_info_text(*info);
  fs::remove(path);
}

TEST(InfoCommand, AnotherFileIsNotPcbAndABrokenOneIsAUsageError) {
  EXPECT_FALSE(read_pcb_file_info(write_file("drawing.dxf", "0\nEOF\n")).has_value());
  const std::string broken = write_file("broken.drl", "M48\nMETRIC\nT1C\n%\nT1\nX1Y1\nM30\n");
  try {
    read_pcb_file_info(broken);
    FAIL() << "read a drill file with a tool without a diameter";
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitUsage);
  }
}

TEST(InfoCommand, ADrawingsCurvesAndTheirFirmwarePoints) {
  Drawing d = test::drawing_of({test::line_curve(0, 0, 10, 0), test::line_curve(20, 5, 20, 15)});
  d.path = "two-lines.dxf";
  const nlohmann::json j = drawing_info_json(d);
  ASSERT_EQ(j["curves"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["curves"][1]["end_mm"][1].get<double>(), 15.0);
  EXPECT_DOUBLE_EQ(j["extents_mm"]["width"].get<double>(), 20.0);
  const std::string text = drawing_info_text(d);
  EXPECT_NE(text.find("curves:   2"), std::string::npos) << text;
  const std::vector<Point2> pts = curve_points(d, 0, points_tolerance_um(0.005));
  ASSERT_GE(pts.size(), 2u);
  EXPECT_NEAR(pts.back().x(), 10.0, 1e-3);
  EXPECT_EQ(points_tolerance_um(0.005), 5);
  for (double bad : {0.0005, 11.0}) {
    try {
      points_tolerance_um(bad);
      FAIL() << bad;
    } catch (const CommandFailure& e) {
      EXPECT_EQ(e.code, kExitUsage);
    }
  }
}

}  // namespace
}  // namespace host::commands
