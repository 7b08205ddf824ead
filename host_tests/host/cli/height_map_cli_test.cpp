// `run` with a simulated warped blank: --probe writes a map the controller follows, a map
// the job leaves is refused before it starts, bad --surface / --probe use is a usage error.
#include <gtest/gtest.h>

#include <filesystem>         // temp paths
#include <fstream>            // std::ifstream
#include <nlohmann/json.hpp>  // nlohmann::json
#include <utility>            // std::pair
#include <vector>             // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::run_tool;
using host_tests::ToolRun;

const std::string kExe = ENGRAVER_EXE;
const std::string kWord = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

std::string out_dir(const std::string& name) {
  const std::string d = testing::TempDir() + "/hm_cli_" + name + "_" + std::to_string(getpid());
  std::filesystem::remove_all(d);
  return d;
}

TEST(HeightMapCli, RunProbesTheSimulatedBlankAndFollowsTheMap) {
  const std::string dir = out_dir("probe");
  const ToolRun r = run_tool(
      kExe, "run " + kWord + " --surface tilt=0.1mm,bow=0.2mm,noise=2um --probe -o " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("engraver: probed "), std::string::npos) << r.err;
  const host::heightmap::HeightMap map =
      host::heightmap::read_height_map_file(dir + "/engraver-word.map.json");
  EXPECT_GT(map.max_um() - map.min_um(), 100.0);  // the tilt and bow were probed
  EXPECT_TRUE(std::filesystem::exists(dir + "/engraver-word.map.svg"));
  std::ifstream in(dir + "/engraver-word.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["outcome"], "completed");
  EXPECT_EQ(j["height_map"]["rows"], map.rows);
  EXPECT_GT(j["height_map"]["frames"].get<int>(), 1);
  std::filesystem::remove_all(dir);
}

TEST(HeightMapCli, AJobLeavingItsMapIsRefusedBeforeItStarts) {
  const std::string dir = out_dir("leave");
  std::filesystem::create_directories(dir);
  host::heightmap::HeightMap m;
  m.origin_x_mm = 4;
  m.origin_y_mm = 4;
  m.pitch_x_mm = m.pitch_y_mm = 10;
  m.rows = m.cols = 2;
  m.heights_um = {0, 10, 20, 30};
  host::heightmap::write_height_map_file(m, dir + "/small.map.json");
  const ToolRun r =
      run_tool(kExe, "run " + kWord + " --height-map " + dir + "/small.map.json -o " + dir);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("the map covers only (4.000, 4.000) .. (14.000, 14.000) mm"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the job was not started"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir + "/engraver-word.json"));
  std::filesystem::remove_all(dir);
}

TEST(HeightMapCli, ASurfaceLengthWithoutItsUnitIsAUsageError) {
  const std::string dir = out_dir("bad");
  ToolRun r = run_tool(kExe, "run " + kWord + " --surface tilt=0.1 -o " + dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--surface: tilt=0.1: give the length with its unit"), std::string::npos)
      << r.err;
  std::filesystem::remove_all(dir);
}

// `run --probe` without `--surface` is refused as the command line is read, in the words of
// the other options that need another: before the input is read (a file that does not
// exist would otherwise be named first) and before anything is planned.
TEST(HeightMapCli, RunProbeWithoutASurfaceIsRefusedAsTheCommandLineIsRead) {
  const std::string dir = out_dir("nosurface");
  for (const std::string& input : {kWord, dir + "/no-such-drawing.dxf"}) {
    const ToolRun r = run_tool(kExe, "run " + input + " --probe -o " + dir);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("engraver: --probe requires --surface\n", 0), 0u) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir));  // nothing planned, nothing written
}

// --surface's refusals show each value as typed (a converted, rounded figure read as inside
// its range), name a repeated key as typed, and take counts by the rule of every count.
TEST(HeightMapCli, SurfaceRefusalsShowTheValueAsTyped) {
  const std::string dir = out_dir("typed");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"tilt=1.0000001mm",
       "--surface: tilt=1.0000001mm: 1.0000001mm is outside the allowed "
       "range -1 .. 1 mm\n"},
      {"noise=100.00001um",
       "--surface: noise=100.00001um: 100.00001um is outside the allowed "
       "range 0 .. 100 um\n"},
      {"bump=1mm:1mm:2mm:1000.0001um",
       "--surface: bump=1mm:1mm:2mm:1000.0001um: the height 1000.0001um is outside the allowed "
       "range -1000 .. 1000 um\n"},
      {"tilt=1mm,tilt=2mm",
       "--surface: 'tilt' is given twice ('tilt=1mm' and 'tilt=2mm'): "
       "give each key once\n"},
      {"tilt=1mm,tilt_x=2mm",
       "--surface: 'tilt_x' is given twice ('tilt=1mm' and 'tilt_x=2mm'; "
       "tilt and tilt_x are one key): give each key once\n"},
      {"seed=1.5", "--surface: seed=1.5: '1.5' is not a whole number\n"},
      {"seed=1e30",
       "--surface: seed=1e30: 1e30 is outside the allowed range 0 .. "
       "1000000000000000\n"},
      {"seed=-1", "--surface: seed=-1: -1 is outside the allowed range 0 .. 1000000000000000\n"},
  };
  for (const auto& c : cases) {
    const ToolRun r = run_tool(kExe, "run " + kWord + " --surface " + c.first + " -o " + dir);
    EXPECT_EQ(r.code, 2) << c.first << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("engraver: " + c.second, 0), 0u) << c.first << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// A unit inside the number: the same words as any other number option.
TEST(HeightMapCli, AUnitInASurfaceNumberIsWordedAsForOtherOptions) {
  const std::string dir = out_dir("inch");
  const ToolRun depth = run_tool(kExe, "run " + kWord + " --feed 0.1in -o " + dir);
  const ToolRun tilt = run_tool(kExe, "run " + kWord + " --surface tilt=0.1in -o " + dir);
  EXPECT_EQ(depth.code, 2);
  EXPECT_EQ(tilt.code, 2);
  EXPECT_EQ(depth.err.rfind("engraver: --feed: '0.1in' is not a decimal number\n", 0), 0u)
      << depth.err;
  EXPECT_EQ(tilt.err.rfind("engraver: --surface: tilt=0.1in: '0.1in' is not a decimal number\n", 0),
            0u)
      << tilt.err;
}

// seed=1e0 is the whole number 1, as --passes 1e0 is 1: the same blank as seed=1.
TEST(HeightMapCli, ASurfaceSeedIsACountAsEveryOther) {
  const std::string dir = out_dir("seed");
  const ToolRun r =
      run_tool(kExe, "run " + kWord + " --surface tilt=0.1mm,noise=2um,seed=1e0 -o " + dir);
  EXPECT_EQ(r.code, 0) << r.err;
  std::filesystem::remove_all(dir);
}

// A map file whose number JSON allows but a double does not hold: bad input (2) naming the
// file, before any connection (port 9: nothing listens there), not an internal error (70).
TEST(HeightMapCli, AMapWithANumberBeyondADoubleIsBadInput) {
  const std::string dir = out_dir("huge");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/huge.map.json";
  std::ofstream(path) << R"({"format": "engraver height map", "version": 1,
    "units": {"xy": "mm", "height": "um"},
    "grid": {"origin_mm": [0, 0], "pitch_mm": [10, 10], "rows": 2, "cols": 2},
    "heights_um": [[0, 1e400], [0, 0]]})";
  for (const std::string& cmd : {"send " + kWord + " --to tcp://127.0.0.1:9 --height-map " + path,
                                 "run " + kWord + " -o " + dir + " --height-map " + path}) {
    const ToolRun r = run_tool(kExe, cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find(path + ": a number beyond the range"), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

// probe (and send --probe) find out that the map cannot be written before anything moves:
// before connecting at all (port 9: nothing listens there), not after probing every point.
TEST(HeightMapCli, AMapThatCannotBeWrittenIsRefusedBeforeProbing) {
  const std::string dir = out_dir("unwritable");
  const std::string path = dir + "/no/such/folder/word.map.json";
  for (const std::string& cmd :
       {"probe " + kWord + " --to tcp://127.0.0.1:9 --height-map " + path,
        "send " + kWord + " --to tcp://127.0.0.1:9 --probe --height-map " + path}) {
    const ToolRun r = run_tool(kExe, cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find(path + ": cannot write the height map there; nothing was probed"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// A number option of the height map's given as NaN passed CLI::Range (every comparison with
// NaN is false): refused as bad input before anything is tried.
TEST(HeightMapCli, NotANumberOptionsAreRefused) {
  const std::string dir = out_dir("nan");
  for (const std::string& cmd :
       {"probe " + kWord + " --to tcp://127.0.0.1:9 --probe-spacing nan",
        "probe " + kWord + " --to tcp://127.0.0.1:9 --outlier-limit nan",
        "run " + kWord + " -o " + dir + " --surface tilt=0.1mm --vbit-angle nan",
        "run " + kWord + " -o " + dir + " --surface tilt=0.1mm --copper-um nan"}) {
    const ToolRun r = run_tool(kExe, cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("'nan' is not a finite number"), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
