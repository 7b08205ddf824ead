// `engraver info` on Gerber and Excellon files, as a user runs it: the layer summary, JSON,
// and a precise refusal with the input exit code.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "host_tests/host/pcb/test_data.h"

#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::ToolRun;

ToolRun run(const std::string& args) {
  return host_tests::run_tool(ENGRAVER_EXE, args);
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PcbInfoCli, GerberSummary) {
  const ToolRun r = run("info " + host::pcb::test::data_file("step_repeat.gbr"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "format:    Gerber RS-274X")) << r.out;
  EXPECT_TRUE(has(r.out, "layer:     unknown")) << r.out;
  EXPECT_TRUE(has(r.out, "units:     mm")) << r.out;
  EXPECT_TRUE(has(r.out, "apertures: 3")) << r.out;
  // Copies 3 x 2 at 5 / 4 mm: x from the pad's 0.5 to the last track's end 3.5 + 10.
  EXPECT_TRUE(has(r.out, "extents:   x 0.500 .. 13.500 mm, y 0.000 .. 6.000 mm")) << r.out;
  EXPECT_TRUE(has(r.out, "polygons:  12 copper areas, 6 holes in them")) << r.out;
}

TEST(PcbInfoCli, ExcellonSummaryAsJson) {
  const ToolRun r = run("info --json " + host::pcb::test::data_file("slots_decimal.drl"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "Excellon");
  EXPECT_EQ(j["layer"], "drill");
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["holes"], 2);
  EXPECT_EQ(j["slots"], 1);
  EXPECT_EQ(j["apertures_or_tools"], 2);
  EXPECT_DOUBLE_EQ(j["tools"]["T2"]["diameter_mm"].get<double>(), 1.2);
  EXPECT_DOUBLE_EQ(j["extents_mm"]["max"][0].get<double>(), 24.6);
}

// `info --json` gave a drawing's width and height but not a Gerber's or an Excellon's: the
// same `extents_mm` fields for every kind, in mm.
TEST(PcbInfoCli, JsonExtentsHaveWidthAndHeightForEveryKind) {
  const ToolRun g = run("info --json " + host::pcb::test::data_file("step_repeat.gbr"));
  ASSERT_EQ(g.code, 0) << g.err;
  const nlohmann::json ge = nlohmann::json::parse(g.out)["extents_mm"];
  EXPECT_NEAR(ge["width"].get<double>(), 13.0, 1e-3) << ge;  // x 0.5 .. 13.5, as the text
  EXPECT_NEAR(ge["height"].get<double>(), 6.0, 1e-3) << ge;
  const ToolRun d = run("info --json " + host::pcb::test::data_file("slots_decimal.drl"));
  ASSERT_EQ(d.code, 0) << d.err;
  const nlohmann::json de = nlohmann::json::parse(d.out)["extents_mm"];
  EXPECT_DOUBLE_EQ(de["width"].get<double>(),
                   de["max"][0].get<double>() - de["min"][0].get<double>());
  EXPECT_DOUBLE_EQ(de["height"].get<double>(),
                   de["max"][1].get<double>() - de["min"][1].get<double>());
}

// "1 holes and slots", "1 copper areas": a count of one in the singular.
TEST(PcbInfoCli, ACountOfOneIsSaidInTheSingular) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-info-one";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/one.drl") << "M48\nMETRIC\nT1C0.800\n%\nG90\nG05\nT1\nX10.0Y10.0\nM30\n";
  std::ofstream(dir + "/one-F.Cu.gbr")
      << "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,1.600000*%\nD10*\nX10000000Y10000000D03*\nM02*\n";
  const ToolRun d = run("info " + dir + "/one.drl");
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_TRUE(has(d.out, "  T1: 0.800 mm, 1 hole or slot\n")) << d.out;
  const ToolRun g = run("info " + dir + "/one-F.Cu.gbr");
  ASSERT_EQ(g.code, 0) << g.err;
  EXPECT_TRUE(has(g.out, "polygons:  1 copper area, 0 holes in them, ")) << g.out;
  std::filesystem::remove_all(dir);
}

TEST(PcbInfoCli, OutlineSummaryAndNotes) {
  const ToolRun r = run("info " + host::pcb::test::data_file("deprecated_inch.gbr"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "units:     inch")) << r.out;
  EXPECT_TRUE(has(r.out, "G54 before an aperture number (deprecated) ignored (3 times)")) << r.out;
  const ToolRun o = run("info " + host::pcb::test::data_file("outline-Edge.Cuts.gbr"));
  EXPECT_TRUE(has(o.out, "layer:     outline")) << o.out;
  EXPECT_TRUE(has(o.out, "paths:     1 centre line (1 closed)")) << o.out;
}

TEST(PcbInfoCli, BadGerberIsAnInputErrorNamingTheLine) {
  const std::string path = testing::TempDir() + "/" + std::to_string(getpid()) + "-bad.gbr";
  std::ofstream(path) << "%FSLAX33Y33*%\n%MOMM*%\nD10*\nM02*\n";
  const ToolRun r = run("info " + path);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "engraver: " + path + ":3: D10 selects an aperture that is not defined\n");
  EXPECT_TRUE(r.out.empty());
}

}  // namespace
