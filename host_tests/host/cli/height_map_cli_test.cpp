// `run` with a simulated warped blank: --probe writes a map the controller follows, a map
// the job leaves is refused before it starts, bad --surface / --probe use is a usage error.
#include <gtest/gtest.h>

#include <filesystem>         // temp paths
#include <fstream>            // std::ifstream
#include <nlohmann/json.hpp>  // nlohmann::json

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

TEST(HeightMapCli, BadSurfaceOrProbeWithoutABlankIsAUsageError) {
  const std::string dir = out_dir("bad");
  ToolRun r = run_tool(kExe, "run " + kWord + " --surface tilt=0.1 -o " + dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--surface: tilt=0.1: give the length with its unit"), std::string::npos)
      << r.err;
  r = run_tool(kExe, "run " + kWord + " --probe -o " + dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("run --probe needs a simulated blank"), std::string::npos) << r.err;
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
