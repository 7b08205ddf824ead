// `engraver board`, and PCB files through `points` and `run`, on a small board written here:
// two pads joined by a track and a square pad (Gerber, mm), a drill file in inches with two
// sizes, and an outline drawn as strokes.
#include <gtest/gtest.h>
#include <sys/stat.h>  // mkfifo
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::ToolRun;

ToolRun run(const std::string& args) {
  return host_tests::run_tool(ENGRAVER_EXE, args);
}

const char* kTopCopper =
    "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n"
    "%ADD10C,1.600000*%\n%ADD11C,0.300000*%\n%ADD12R,2.000000X2.000000*%\n"
    "D10*\nX10000000Y10000000D03*\nX20000000Y10000000D03*\n"
    "D11*\nX10000000Y10000000D02*\nX20000000Y10000000D01*\n"
    "D12*\nX25000000Y15000000D03*\n%EXTRA%M02*\n";

const char* kDrillInch =
    "M48\nINCH\nT1C0.0315\nT2C0.0394\n%\nG90\nG05\nT1\nX0.393701Y0.393701\n"
    "X0.787402Y0.393701\nT2\nX0.984252Y0.590551\nM30\n";

const char* kOutline =
    "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Profile,NP*%\n%ADD10C,0.100000*%\nD10*\n"
    "X0Y0D02*\nX35000000Y0D01*\nX35000000Y25000000D01*\nX0Y25000000D01*\nX0Y0D01*\nM02*\n";

// A directory holding the board; `extra` is spliced into the copper before M02.
std::string write_board(const std::string& name, const std::string& extra = "") {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
  std::filesystem::create_directories(dir);
  std::string top = kTopCopper;
  top.replace(top.find("%EXTRA%"), 7, extra);
  std::ofstream(dir + "/t-F.Cu.gbr") << top;
  std::ofstream(dir + "/t-PTH.drl") << kDrillInch;
  std::ofstream(dir + "/t-Edge.Cuts.gbr") << kOutline;
  return dir;
}

// `info` on a board folder (its help said FILE may be one; it was refused as "is a directory,
// not a drawing file"): which file was taken for which layer and why, which were left out,
// then each layer's summary as for the file alone; both copper sides; exit 0.
TEST(BoardCli, InfoOnABoardFolderSaysWhichFileIsWhichLayer) {
  const std::string dir = write_board("info");
  std::string silk = kTopCopper;
  silk.replace(silk.find("Copper,L1,Top"), 13, "Legend,Top");
  silk.replace(silk.find("%EXTRA%"), 7, "");
  std::ofstream(dir + "/t-F.SilkS.gbr") << silk;
  std::string mask = kTopCopper;  // no X2 file function: the name says what it is
  mask.replace(mask.find("%EXTRA%"), 7, "");
  mask.replace(mask.find("%TF.FileFunction,Copper,L1,Top*%\n"), 33, "");
  std::ofstream(dir + "/t-F.Mask.gbr") << mask;
  std::ofstream(dir + "/notes.txt") << "hello\n";
  const ToolRun r = run("info " + dir + "/");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const std::string& line : std::vector<std::string>{
           "folder:    " + dir + "/ (board '" + std::to_string(getpid()) + "-info', 3 layers read)",
           "  - " + dir + "/t-F.Cu.gbr: taken as copper top (from its X2 file function)",
           "  - " + dir + "/t-PTH.drl: taken as drill (from its name)",
           "  - " + dir + "/t-Edge.Cuts.gbr: taken as outline (from its X2 file function)",
           // What a layer no job cuts is, from its X2 file function or its name (outside
           // tester 20: the guide promised the reason, the note said to name it as copper).
           "  - " + dir +
               "/t-F.SilkS.gbr: a silkscreen layer (from its X2 file function): left out",
           "  - " + dir + "/t-F.Mask.gbr: a solder mask layer (from its name): left out",
           "  - " + dir + "/notes.txt: neither Gerber nor Excellon",
           "file:      " + dir + "/t-PTH.drl", "format:    Excellon", "holes:     3",
           "layer:     outline"}) {
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  }
  const ToolRun j = run("info --json " + dir);
  ASSERT_EQ(j.code, 0) << j.err;
  const nlohmann::json info = nlohmann::json::parse(j.out);
  EXPECT_EQ(info["folder"], dir);
  ASSERT_EQ(info["layers"].size(), 3u) << info.dump(2);
  std::set<std::string> kinds;
  for (const nlohmann::json& l : info["layers"]) kinds.insert(l["layer"].get<std::string>());
  EXPECT_EQ(kinds, (std::set<std::string>{"copper top", "drill", "outline"}));
  EXPECT_EQ(info["files"].size(), 6u) << info.dump(2);
}

// A folder given as `DIR/.` is named after DIR (outside tester 21: `board .` wrote
// `..board.svg` and `..board.json`).
TEST(BoardCli, AFolderGivenAsDotIsNamedAfterItself) {
  const std::string dir = write_board("dot");
  const ToolRun r = run("board " + dir + "/. -o " + dir + "/out");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string name = std::to_string(getpid()) + "-dot";
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + name + ".board.json")) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + name + ".board.svg")) << r.out;
}

TEST(BoardCli, WholeBoardIsPlannedCheckedPlottedAndReported) {
  const std::string dir = write_board("ok");
  const ToolRun r = run("board " + dir + " -o " + dir + "/out --json --wire-bytes");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["islands"], 2);
  EXPECT_EQ(j["holes"], 3);
  EXPECT_EQ(j["holes_on_copper"], 3);  // the inch drill file lines up with the mm copper
  EXPECT_EQ(j["drill_tools"], 2);
  EXPECT_EQ(j["tool_changes"], 3);  // drill 0.8, drill 1.0, cutter (the V-bit is mounted first)
  EXPECT_EQ(j["check"]["copper_hits"], 0);
  EXPECT_EQ(j["check"]["unseparated_pairs"], 0);
  EXPECT_EQ(j["narrow_gaps"].size(), 0u);
  EXPECT_LT(j["isolation_spline_bytes"].get<double>(),
            j["isolation_g1_bytes_same_tolerance"].get<double>());
  // Compact #K data: well under the fixed-width #D frames of the same splines.
  EXPECT_LT(j["isolation_spline_bytes"].get<double>(),
            0.6 * j["isolation_spline_bytes_fixed_width"].get<double>());
  // Bytes per tool, in the order they are mounted, adding up to the job's frames.
  ASSERT_EQ(j["bytes_per_tool"].size(), 4u) << j.dump(2);
  EXPECT_EQ(j["bytes_per_tool"][0]["name"], "V-bit 0.20mm");
  EXPECT_EQ(j["bytes_per_tool"][3]["name"], "Cutter 1.00mm");
  for (const auto& t : j["bytes_per_tool"]) EXPECT_GT(t["bytes"].get<int>(), 0) << t.dump();
  const std::string base = dir + "/out/" + std::to_string(getpid()) + "-ok";
  EXPECT_FALSE(std::filesystem::exists(base + ".board.png"));  // only with --png
  EXPECT_TRUE(std::filesystem::exists(base + ".board.svg"));
  EXPECT_TRUE(std::filesystem::exists(base + ".board.json"));
}

TEST(BoardCli, PngPlotOnlyWhenAskedFor) {
  const std::string dir = write_board("png");
  const std::string base = dir + "/out/" + std::to_string(getpid()) + "-png";
  const ToolRun plain = run("board " + dir + " -o " + dir + "/out");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_TRUE(std::filesystem::exists(base + ".board.svg"));
  EXPECT_FALSE(std::filesystem::exists(base + ".board.png"));
  EXPECT_NE(plain.out.find("plot: " + base + ".board.svg; report:"), std::string::npos)
      << plain.out;
  const ToolRun png = run("board " + dir + " -o " + dir + "/out --png");
  ASSERT_EQ(png.code, 0) << png.err;
  std::ifstream in(base + ".board.png", std::ios::binary);
  std::string magic(4, '\0');
  in.read(&magic[0], 4);
  EXPECT_EQ(magic, "\x89PNG");
  EXPECT_NE(png.out.find("plot: " + base + ".board.svg, .png; report:"), std::string::npos)
      << png.out;
  // A PNG of no plot is a contradiction: refused, not ignored.
  EXPECT_EQ(run("board " + dir + " -o " + dir + "/out --png --no-plot").code, 2);
}

TEST(BoardCli, NarrowGapRefusesTheJobAndNamesThePlace) {
  // A 1 mm pad whose edge is 0.1 mm right of the square pad (x = 26.0).
  const std::string dir = write_board("gap", "%ADD13C,1.000000*%\nD13*\nX26600000Y15000000D03*\n");
  const ToolRun r = run("board " + dir + " -o " + dir + "/out");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.err.find("t-F.Cu.gbr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("gap 0.100 mm < 0.216 mm (tool 0.200 mm + 2 x 0.008 mm clearance)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("at (26.0"), std::string::npos) << r.err;  // between x 26.0 and 26.1
  const ToolRun narrow = run("board " + dir + " -o " + dir + "/out --tool-width 0.08");
  EXPECT_EQ(narrow.code, 0) << narrow.err;
}

// `points --csv` rows of a board job (tool,tool_name,tool_diameter_um,path,point,x_um,y_um,
// z_um).
struct PointRow {
  int tool = 0;
  std::string tool_name;
  double tool_diameter_um = 0;
  int path = 0, point = 0;
  double x_um = 0, y_um = 0, z_um = 0;
};

std::vector<PointRow> point_rows(const std::string& csv, std::string* header) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, *header);
  std::vector<PointRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream l(line);
    for (std::string x; std::getline(l, x, ',');) f.push_back(x);
    EXPECT_EQ(f.size(), 8u) << line;
    if (f.size() != 8) continue;
    rows.push_back(PointRow{std::stoi(f[0]), f[1], std::stod(f[2]), std::stoi(f[3]),
                            std::stoi(f[4]), std::stod(f[5]), std::stod(f[6]), std::stod(f[7])});
  }
  return rows;
}

TEST(BoardCli, AnOpeningThatHoldsNoIslandIsCutOnlyWhenAsked) {
  // A 4 mm square pad with a 1 mm clear square in its middle: an opening with nothing in it.
  const std::string dir = write_board(
      "opening",
      "%ADD13R,4.000000X4.000000*%\n%ADD14R,1.000000X1.000000*%\nD13*\nX30000000Y5000000D03*\n"
      "%LPC*%\nD14*\nX30000000Y5000000D03*\n%LPD*%\n");
  const ToolRun r = run("board " + dir + " -o " + dir + "/out --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["isolation_contours"], 3);
  // One opening, said in the singular (it read "1 opening(s) ... hold ... them").
  EXPECT_NE(r.err.find("t-F.Cu.gbr: 1 opening in the copper holds no other island (a hatched "
                       "pour): no contour inside it (--isolate-empty-holes cuts it)\n"),
            std::string::npos)
      << r.err;
  const ToolRun all = run("board " + dir + " -o " + dir + "/out --json --isolate-empty-holes");
  ASSERT_EQ(all.code, 0) << all.err;
  EXPECT_EQ(nlohmann::json::parse(all.out)["isolation_contours"], 4);
}

TEST(BoardCli, PointsOnACopperLayerAreToolCentresAroundTheCopper) {
  const std::string dir = write_board("points");
  const ToolRun r = run("points " + dir + "/t-F.Cu.gbr --csv");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string header;
  const std::vector<PointRow> rows = point_rows(r.out, &header);
  EXPECT_EQ(header, "tool,tool_name,tool_diameter_um,path,point,x_um,y_um,z_um");
  double min_x = 1e9, max_x = -1e9;
  for (const PointRow& p : rows) {
    EXPECT_EQ(p.tool, 1);
    EXPECT_EQ(p.tool_name, "V-bit 0.20mm");
    EXPECT_EQ(p.tool_diameter_um, 200);
    EXPECT_EQ(p.z_um, -50);  // the isolation depth
    min_x = std::min(min_x, p.x_um), max_x = std::max(max_x, p.x_um);
  }
  EXPECT_GT(rows.size(), 20u);
  // Pad edges less / plus the tool radius and the 8 um clearance, file frame.
  EXPECT_NEAR(min_x, (10 - 0.8 - 0.108) * 1000, 6);
  EXPECT_NEAR(max_x, (26 + 0.108) * 1000, 6);
}

// `points` plans with the board options, as `board` and `run` do: the tool width, passes,
// clearance and side reach the paths, and every tool of a board folder is listed.
TEST(BoardCli, PointsTakeTheBoardOptionsAndListEveryTool) {
  const std::string dir = write_board("points-options");
  const ToolRun r = run("points " + dir +
                        " --csv --tool-width 0.1 --passes 2 --overlap 0.5 --clearance 0.02 "
                        "--side top");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string header;
  const std::vector<PointRow> rows = point_rows(r.out, &header);
  double min_x = 1e9;
  std::set<std::string> tools;
  int last_path = -1, last_point = -1;
  for (const PointRow& p : rows) {
    tools.insert(std::to_string(p.tool) + " " + p.tool_name);
    if (p.tool == 1) min_x = std::min(min_x, p.x_um);
    // Points numbered from 0 within each path, paths in order.
    if (p.path != last_path) {
      EXPECT_EQ(p.path, last_path + 1);
      EXPECT_EQ(p.point, 0);
    } else {
      EXPECT_EQ(p.point, last_point + 1);
    }
    last_path = p.path, last_point = p.point;
  }
  EXPECT_EQ(tools, (std::set<std::string>{"1 V-bit 0.10mm", "2 Drill 0.80mm", "3 Drill 1.00mm",
                                          "4 Cutter 1.00mm"}));
  // The second pass of a 0.1 mm tool, half overlapping: 0.05 + 0.02 + 0.05 mm out of the pad.
  EXPECT_NEAR(min_x, (10 - 0.8 - 0.12) * 1000, 6);
  // Holes: one point each at the drill's depth, in the files' frame (inch file, mm copper).
  int holes = 0;
  for (const PointRow& p : rows) {
    if (p.tool_name.rfind("Drill", 0) != 0) continue;
    ++holes;
    EXPECT_EQ(p.z_um, -1800);
  }
  EXPECT_EQ(holes, 3);
  // The bottom side is mirrored for the machine, but the points stay in the files' frame.
  std::string bottom_copper = kTopCopper;
  bottom_copper.replace(bottom_copper.find("L1,Top"), 6, "L2,Bot");
  bottom_copper.replace(bottom_copper.find("%EXTRA%"), 7, "");
  std::ofstream(dir + "/t-B.Cu.gbr") << bottom_copper;
  const ToolRun bottom = run("points " + dir + "/t-B.Cu.gbr --csv --tool-width 0.1");
  ASSERT_EQ(bottom.code, 0) << bottom.err;
  double bottom_min_x = 1e9;
  for (const PointRow& p : point_rows(bottom.out, &header))
    bottom_min_x = std::min(bottom_min_x, p.x_um);
  EXPECT_NEAR(bottom_min_x, (10 - 0.8 - 0.058) * 1000, 6);
  // Board options are refused for drawings.
  const ToolRun drawing =
      run("points " + std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf --passes 2");
  EXPECT_EQ(drawing.code, 2);
  EXPECT_NE(drawing.err.find("--passes is for PCB files"), std::string::npos) << drawing.err;
}

// A clearing tool from the command line: a second tool after the V-bit, its bytes reported.
TEST(BoardCli, ClearingToolIsASecondToolWithItsBytesReported) {
  const std::string dir = write_board("clearing");
  std::filesystem::remove(dir + "/t-PTH.drl");
  std::filesystem::remove(dir + "/t-Edge.Cuts.gbr");
  const ToolRun r = run("board " + dir + " -o " + dir +
                        "/out --json --no-plot --tool-width 0.1 --passes 8 --clearing-tool 0.6");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["bytes_per_tool"].size(), 2u) << j.dump(2);
  EXPECT_EQ(j["bytes_per_tool"][1]["name"], "Clear 0.60mm");
  EXPECT_EQ(j["tool_changes"], 1);
  EXPECT_EQ(j["check"]["copper_hits"], 0);
  const ToolRun same =
      run("board " + dir + " -o " + dir + "/out --tool-width 0.1 --passes 8 --clearing-tool 0.1");
  EXPECT_EQ(same.code, 2) << same.err;  // bad input naming both options (was 1, unnamed)
  EXPECT_NE(same.err.find("--clearing-tool (0.1 mm) must be wider than --tool-width (0.1 mm)"),
            std::string::npos)
      << same.err;
}

// A double-sided board's second setup, simulated end to end: the flipped blank sits 0.3 mm
// and 0.5 degrees off on its pins; the simulated operator measures the two alignment holes,
// the job is turned and shifted onto them and cuts within 10 um of where the bottom copper
// lies under the top side's frame. On the pins alone the same blank is cut 0.3 mm off,
// through copper (exit 8).
TEST(BoardCli, FlippedBlankOffByAFewTenthsIsCutWhereItBelongsAfterMeasuringTheHoles) {
  const std::string dir = write_board("flip");
  std::string bottom_copper = kTopCopper;
  bottom_copper.replace(bottom_copper.find("L1,Top"), 6, "L2,Bot");
  bottom_copper.replace(bottom_copper.find("%EXTRA%"), 7, "");
  std::filesystem::remove(dir + "/t-F.Cu.gbr");
  std::ofstream(dir + "/t-B.Cu.gbr") << bottom_copper;
  const std::string job = "run " + dir + " --side bottom --align-holes auto --cut-step 1.8 ";
  const ToolRun aligned = run(job + "-o " + dir + "/aligned --blank-error 0.3 -0.2 0.5");
  ASSERT_EQ(aligned.code, 0) << aligned.err << aligned.out;
  const std::string name = std::to_string(getpid()) + "-flip";
  const nlohmann::json a = nlohmann::json::parse(std::ifstream(dir + "/aligned/" + name + ".json"));
  EXPECT_EQ(a["flip"]["aligned"], true);
  EXPECT_NEAR(a["flip"]["alignment"]["rotation_deg"].get<double>(), 0.5, 0.01);
  EXPECT_LT(a["registration_error"]["max_um"].get<double>(), 10.0) << a["registration_error"];
  EXPECT_GT(a["registration_error"]["samples"].get<int>(), 1000);
  EXPECT_EQ(a["simulated_isolation_check"]["copper_hits"], 0);
  EXPECT_NE(aligned.out.find("the job aligned to the measured holes"), std::string::npos);

  const ToolRun pins = run(job + "-o " + dir + "/pins --blank-error 0.3 -0.2 0.5 --pins-only");
  EXPECT_EQ(pins.code, 8) << pins.err << pins.out;
  const nlohmann::json p = nlohmann::json::parse(std::ifstream(dir + "/pins/" + name + ".json"));
  EXPECT_GT(p["registration_error"]["max_um"].get<double>(), 300.0) << p["registration_error"];
  EXPECT_GT(p["simulated_isolation_check"]["copper_hits"].get<int>(), 0);

  // A blank error needs alignment holes to measure.
  const ToolRun none = run("run " + dir + " --side bottom -o " + dir + "/none --blank-error 0 0 1");
  EXPECT_EQ(none.code, 2) << none.err;
  EXPECT_NE(none.err.find("--align-holes"), std::string::npos) << none.err;
}

// The simulated machine's cuts with a clearing tool: each tool's paths swept by its own
// radius; the wide tool's edge stays 83 um from the copper (clearance 8 um + one 0.1 mm pass
// less its 25 um overlap) less the machine's contour error.
TEST(BoardCli, RunChecksTheClearingToolsCutsWithItsOwnRadius) {
  const std::string dir = write_board("clearing-run");
  std::filesystem::remove(dir + "/t-PTH.drl");
  std::filesystem::remove(dir + "/t-Edge.Cuts.gbr");
  const ToolRun r = run("run " + dir + " -o " + dir +
                        "/out --tool-width 0.1 --passes 6 --clearing-tool 0.4 --allow-narrow-gaps");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(
      std::ifstream(dir + "/out/" + std::to_string(getpid()) + "-clearing-run.json"));
  const nlohmann::json& c = j["simulated_isolation_check"];
  EXPECT_EQ(c["copper_hits"], 0) << c.dump();
  ASSERT_TRUE(c.contains("clearing_tool_min_clearance_um")) << c.dump();
  EXPECT_GT(c["clearing_tool_min_clearance_um"].get<double>(), 83.0 - 10.0) << c.dump();
  EXPECT_LT(c["clearing_tool_min_clearance_um"].get<double>(), 83.0 + 10.0) << c.dump();
  EXPECT_GT(c["min_clearance_um"].get<double>(), 0.0) << c.dump();
}

// The help of `points` and `info` names the PCB inputs both read.
TEST(BoardCli, PointsAndInfoHelpNameThePcbInputs) {
  for (const char* cmd : {"points", "info"}) {
    const ToolRun r = run(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.out.find("Gerber, Excellon, a board folder"), std::string::npos) << r.out;
  }
}

TEST(BoardCli, RunSimulatesTheWholeBoardWithDrillingAndToolChanges) {
  // With a 0.2 mm via pad: the tool goes round it on a 0.21 mm arc, where the controller's
  // chords cut toward the copper.
  const std::string dir = write_board("run", "%ADD13C,0.200000*%\nD13*\nX14000000Y14000000D03*\n");
  // A trailing '/' as shell completion writes it: the outputs still take the folder's name.
  const ToolRun r = run("run " + dir + "/ -o " + dir + "/out --cut-step 1.8");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const std::string base = dir + "/out/" + std::to_string(getpid()) + "-run";
  EXPECT_TRUE(std::filesystem::exists(base + ".svg"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(base + ".json"));
  EXPECT_EQ(j["outcome"], "completed");
  EXPECT_FALSE(std::filesystem::exists(base + ".board.png"));  // only with --png
  // The simulated tool centres at the isolation depth (not only the planned paths) keep the
  // tool off the copper: the board's check on the trace, every isolation contour cut, and
  // the tool's edge no closer to copper than the planned paths' fit tolerance plus the
  // planner's corner budget (4 um ramp + 2 um early switch); on this board, with a board's
  // 1 um chords, the machine loses under 3 um of the planned clearance (4.4 um with 5 um
  // chords, the drawings' default).
  const nlohmann::json& c = j["simulated_isolation_check"];
  ASSERT_TRUE(c.is_object()) << j.dump(2);
  EXPECT_EQ(c["copper_hits"], 0) << c.dump();
  EXPECT_EQ(c["unseparated_pairs"], 0) << c.dump();
  EXPECT_GT(c["samples"].get<int>(), 1000);
  EXPECT_GE(c["min_clearance_um"].get<double>(),
            c["planned_min_clearance_um"].get<double>() - 4.0 - 2.0)
      << c.dump();
  EXPECT_GE(c["min_clearance_um"].get<double>(), c["planned_min_clearance_um"].get<double>() - 3.0)
      << c.dump();
  EXPECT_NE(r.out.find("simulated isolation cuts"), std::string::npos) << r.out;
  // Places name their frame, as the other report lines do ("in the files", "on the machine").
  const std::string at = R"(at \(-?[0-9.]+, -?[0-9.]+\) mm on the machine)";
  EXPECT_TRUE(std::regex_search(r.out, std::regex("max contour error [0-9.]+ um " + at + ";")))
      << r.out;
  EXPECT_TRUE(std::regex_search(
      r.out, std::regex("least clearance of the tool's edge -?[0-9.]+ um " + at + " \\(planned")))
      << r.out;
}

// Without an outline nothing cuts below the drill start height, so the pen-down threshold
// once fell above it: the travel from hole to hole (at +0.5 mm) counted as cutting, in the
// traced length, the contour error (mm) and the plot. Copper with drilling, and drilling
// alone.
TEST(BoardCli, RunOfABoardWithoutOutlineCountsNoDrillTravelAsCutting) {
  const std::string dir = write_board("no-outline");
  std::filesystem::remove(dir + "/t-Edge.Cuts.gbr");
  for (const std::string& input : {dir, dir + "/t-PTH.drl"}) {
    const ToolRun r = run("run " + input + " -o " + dir + "/out");
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    const nlohmann::json j = nlohmann::json::parse(
        std::ifstream(dir + "/out/" + std::filesystem::path(input).stem().string() + ".json"));
    EXPECT_NEAR(j["traced_cut_mm"].get<double>(), j["planned_cut_mm"].get<double>(), 0.5) << input;
    EXPECT_LT(j["max_contour_error_um"].get<double>(), 10.0) << input;
    EXPECT_GT(j["traced_rapid_mm"].get<double>(), 20.0) << input;  // hole to hole
  }
}

// A job that would cut copper is a failed job (exit 8), refused before anything runs: with
// no clearance and 30 um chords, the controller's points round the pads sag into the copper.
// `send` refuses before it connects (the address here would fail with 6), `run` before it
// simulates.
TEST(BoardCli, AJobWhoseControllerPointsCutCopperIsRefusedBySendAndRun) {
  const std::string dir = write_board("cuts", "%ADD13C,0.200000*%\nD13*\nX14000000Y14000000D03*\n");
  const std::string options = " --clearance 0 --tol 0.03";
  const ToolRun send = run("send " + dir + options + " --to tcp://127.0.0.1:1");
  EXPECT_EQ(send.code, 8) << send.err;
  EXPECT_NE(send.err.find("the job would cut copper: the controller's points at 0.03 mm chords "
                          "cut into copper in "),
            std::string::npos)
      << send.err;
  EXPECT_EQ(send.err.find("cannot connect"), std::string::npos) << send.err;
  const ToolRun sim = run("run " + dir + options + " -o " + dir + "/out");
  EXPECT_EQ(sim.code, 8) << sim.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << "simulated although refused";
  // The default chords (1 um) keep the tool off the copper.
  EXPECT_EQ(run("send " + dir + " --clearance 0 --to tcp://127.0.0.1:1").code, 6);
}

// `run`'s own check of the simulated tool path: on a real board without clearance the
// machine's contour error takes the tool into the copper (32 places, 5.9 um), which the
// controller's points alone do not show; the job is failed (exit 8), not reported as done.
TEST(BoardCli, RunFailsAJobWhoseSimulatedPathCutsCopper) {
  const std::string board =
      std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/pcb/multivibrator";
  if (!std::filesystem::is_directory(board)) GTEST_SKIP() << board << " (shared samples) absent";
  const std::string out = testing::TempDir() + "/" + std::to_string(getpid()) + "-sim-cuts";
  const ToolRun r = run("run " + board + " --clearance 0 -o " + out);
  EXPECT_EQ(r.code, 8) << r.err;
  EXPECT_NE(r.err.find("the job would cut copper: the simulated tool path cut into copper in "),
            std::string::npos)
      << r.err;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/multivibrator.json"));
  EXPECT_GT(j["simulated_isolation_check"]["copper_hits"].get<int>(), 0);
}

// Islands left joined only across the narrow gaps allowed pass the check, and the summary and
// the report say so (outside tester 18: "check: 0 copper hits, 7 pairs ..." with exit 0 did
// not say whether it passed).
TEST(BoardCli, AllowedNarrowGapsPassTheCheckAndTheSummarySaysSo) {
  const std::string board =
      std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/pcb/multivibrator";
  if (!std::filesystem::is_directory(board)) GTEST_SKIP() << board << " (shared samples) absent";
  const std::string out = testing::TempDir() + "/" + std::to_string(getpid()) + "-allowed";
  const ToolRun r =
      run("board " + board + " --tool-width 1.5 --allow-narrow-gaps --no-plot -o " + out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\n  check: passed: no copper cut; "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" pairs of islands not separated, across the "), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/multivibrator.board.json"));
  EXPECT_EQ(j["check"]["passed"], true);
  EXPECT_GT(j["check"]["unseparated_pairs"].get<int>(), 0);
}

// The guide's double-sided workflow on the shared multivibrator, as printed there: the hole
// positions the report lists, the measured holes the simulated operator finds for a blank
// 0.3 mm, -0.2 mm and 0.5 degrees off, the alignment found from them, and the cut within
// 10 um (pins only: exit 8).
TEST(BoardCli, GuidesDoubleSidedWorkflowOnTheMultivibrator) {
  const std::string board =
      std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/pcb/multivibrator";
  if (!std::filesystem::is_directory(board)) GTEST_SKIP() << board << " (shared samples) absent";
  const std::string out = testing::TempDir() + "/" + std::to_string(getpid()) + "-double";
  const ToolRun b = run("board " + board + " --side bottom --align-holes auto -o " + out);
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.out.find("  alignment hole 1 at (30.495, 8.500) mm\n"
                       "  alignment hole 2 at (30.495, 49.250) mm\n"),
            std::string::npos)
      << b.out;
  const ToolRun m = run("board " + board +
                        " --side bottom --align-holes auto --align-measured 30.973 8.301 30.617 "
                        "49.049 --json --no-plot -o " +
                        out);
  ASSERT_EQ(m.code, 0) << m.err;
  const nlohmann::json mj = nlohmann::json::parse(m.out);
  EXPECT_NEAR(mj["alignment"]["placement"]["rotation_deg"].get<double>(), 0.5, 0.002);
  const ToolRun r = run("run " + board + " --side bottom --align-holes auto --blank-error 0.3 " +
                        "-0.2 0.5 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("double-sided: blank placed off by (0.300, -0.200) mm and 0.50 deg; the "
                       "job aligned to the measured holes; the cuts land "),
            std::string::npos)
      << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/multivibrator.json"));
  EXPECT_EQ(j["flip"]["measured_holes_mm"],
            nlohmann::json::parse("[30.973, 8.301, 30.617, 49.049]"));
  EXPECT_LT(j["registration_error"]["max_um"].get<double>(), 10.0);
  const ToolRun pins = run("run " + board +
                           " --side bottom --align-holes auto --blank-error 0.3 -0.2 0.5 "
                           "--pins-only -o " +
                           out);
  EXPECT_EQ(pins.code, 8) << pins.err;
}

// A work area beyond the controller's travel is refused by `board` as by `run` (one check):
// `board` once planned it and exited 0, and `run` then refused the job.
TEST(BoardCli, AWorkAreaBeyondTheControllersTravelIsRefusedByBoardAsByRun) {
  const std::string dir = write_board("work");
  for (const std::string command : {"board", "run"}) {
    const ToolRun r = run(command + " " + dir + " -o " + dir + "/out --work 300 300");
    EXPECT_EQ(r.code, 1) << command << ": " << r.err;
    EXPECT_NE(r.err.find("--work 300 300 mm is beyond the controller's travel of 297 x 210 mm"),
              std::string::npos)
        << command << ": " << r.err;
  }
  EXPECT_EQ(run("board " + dir + " -o " + dir + "/out --work 297 210").code, 0);
}

// EAGLE and Fritzing write their drill file as .txt starting with '%' then M48: recognised
// by its content in a folder (it was left out without a word: no holes, exit 0).
TEST(BoardCli, AFoldersTxtDrillFileIsRecognisedByItsContent) {
  const std::string dir = write_board("txt-drill");
  std::filesystem::remove(dir + "/t-PTH.drl");
  std::ofstream(dir + "/t.txt") << "%\n" << kDrillInch;
  std::ofstream(dir + "/readme.txt") << "Made with EAGLE\n";
  const ToolRun r = run("board " + dir + " -o " + dir + "/out --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["holes"], 3);
  // Every file left out is named, with the reason.
  EXPECT_NE(r.err.find("readme.txt: neither Gerber nor Excellon (by its name or content): left "
                       "out"),
            std::string::npos)
      << r.err;
}

// OrCAD's .drd is a drill drawing in Gerber: in a folder it is no drill file, and the
// command says so (it was taken as the drill file: "0 holes (no drill file)", not a word why).
// The same for a Gerber under any drill name (outside tester 24: a .drl holding Gerber refused
// the whole folder, "unknown or unsupported command").
TEST(BoardCli, AFoldersGerberDrdIsNotTakenAsTheDrillFile) {
  for (const char* name : {"t.drd", "holes.drl", "holes.xln", "holes.exc"}) {
    SCOPED_TRACE(name);
    const std::string dir = write_board(std::string("gerber-drill-") + name);
    std::filesystem::remove(dir + "/t-PTH.drl");
    std::ofstream(dir + "/" + name)
        << "*\n%MOIN*%\n%FSLAX34Y34*%\n%ADD10C,.01*%\nD10*\nX0Y0D03*\nM02*\n";
    const ToolRun r = run("board " + dir + " -o " + dir + "/out --json --no-plot");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["holes"], 0);
    EXPECT_NE(
        r.err.find(std::string(name) + ": holds Gerber, not Excellon: no drill file (left out)"),
        std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find(std::string(name) + ": taken as drill"), std::string::npos) << r.err;
    // Named as the drill file, it is refused, not read as a file without holes.
    const ToolRun named = run("board --top " + dir + "/t-F.Cu.gbr --drill " + dir + "/" + name +
                              " -o " + dir + "/out --no-plot");
    EXPECT_EQ(named.code, 2) << named.err;
    EXPECT_NE(named.err.find(std::string(name) + ": holds Gerber, not Excellon: no drill file"),
              std::string::npos)
        << named.err;
  }
}

// A folder job whose copper is not recognised is not a success: planning its holes alone
// looked like one (exit 0).
TEST(BoardCli, AFolderWithoutCopperIsRefused) {
  const std::string dir = write_board("no-copper");
  std::filesystem::remove(dir + "/t-F.Cu.gbr");
  std::string plain = kTopCopper;  // no X2 file function, a name that says nothing
  plain.replace(plain.find("%EXTRA%"), 7, "");
  plain.replace(plain.find("%TF.FileFunction,Copper,L1,Top*%\n"), 33, "");
  std::ofstream(dir + "/t-layer1.gbr") << plain;
  const ToolRun r = run("board " + dir + " -o " + dir + "/out");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("no copper layer for the job among the folder's files"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("t-layer1.gbr: neither its name nor an X2 file function says"),
            std::string::npos)
      << r.err;
}

// A folder of the other side's copper only, with --side for this one: the message says which
// side its copper is (it offered only to name the copper or give a file alone; outside
// tester 17).
TEST(BoardCli, AFolderOfTheOtherSidesCopperSaysWhichSideToAskFor) {
  const std::string dir = write_board("other-side");
  const ToolRun r = run("board " + dir + " --side top -o " + dir + "/out");  // top copper too
  EXPECT_EQ(r.code, 0) << r.err;
  std::filesystem::remove(dir + "/t-F.Cu.gbr");
  std::string bottom = kTopCopper;
  bottom.replace(bottom.find("%EXTRA%"), 7, "");
  bottom.replace(bottom.find("Copper,L1,Top"), 13, "Copper,L2,Bot");
  std::ofstream(dir + "/t-B.Cu.gbr") << bottom;
  const ToolRun top = run("board " + dir + " --side top -o " + dir + "/out");
  EXPECT_EQ(top.code, 2) << top.err;
  EXPECT_NE(top.err.find("no copper layer for the job among the folder's files (its copper is "
                         "bottom copper: give --side bottom; "),
            std::string::npos)
      << top.err;
}

// A binary file with a plain Gerber name (an outside tester's /bin/ls as x.gbr) is left out as
// binary data, in the readers' words; it was "neither its name nor an X2 file function says
// copper" with advice to name it with --top. A FIFO in the folder is listed as left out, never
// opened (it was silently not listed).
TEST(BoardCli, ABinaryFileOrAFifoInABoardFolderIsLeftOutSayingWhy) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-bingbr";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/x.gbr", std::ios::binary) << std::string(
      "\x7F"
      "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0>\0\nmore",
      24);
  ASSERT_EQ(mkfifo((dir + "/zz.gbr").c_str(), 0644), 0);
  const std::string timed = std::string("timeout 10 ") + ENGRAVER_EXE;
  const ToolRun info = host_tests::run_tool(timed, "info " + dir);
  EXPECT_EQ(info.code, 0) << info.err;
  EXPECT_NE(
      info.out.find("  - " + dir +
                    "/x.gbr: not a Gerber file: binary data (a NUL byte at byte 7): left out"),
      std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("  - " + dir +
                          "/zz.gbr: not a regular file (a pipe, device or socket): left out"),
            std::string::npos)
      << info.out;
  const ToolRun board = host_tests::run_tool(timed, "board " + dir + " -o " + dir + "/out");
  EXPECT_EQ(board.code, 2) << board.err;
  EXPECT_NE(board.err.find("x.gbr: not a Gerber file: binary data"), std::string::npos)
      << board.err;
  EXPECT_EQ(board.err.find("--top"), std::string::npos) << board.err;
  std::filesystem::remove_all(dir);
}

// An option names the layer whatever the file's name says: a copper file named "outline"
// given with --top is copper (it was read as outline strokes).
TEST(BoardCli, AnExplicitTopOptionWinsOverAnOutlineName) {
  const std::string dir = write_board("explicit");
  std::string top = kTopCopper;
  top.replace(top.find("%EXTRA%"), 7, "");
  top.replace(top.find("%TF.FileFunction,Copper,L1,Top*%\n"), 33, "");
  std::ofstream(dir + "/board-outline-copper.gbr") << top;
  const ToolRun r =
      run("board --top " + dir + "/board-outline-copper.gbr -o " + dir + "/out --json --no-plot");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["islands"], 2);
}

// KiCad writes an Edge.Cuts file holding only its aperture list when no outline is drawn:
// the board is planned without a cut-out, and says so (it was refused whole: "the outline
// layer has no closed loop").
TEST(BoardCli, AnEmptyOutlineFilePlansTheBoardWithoutACutout) {
  const std::string dir = write_board("empty-outline");
  std::ofstream(dir + "/t-Edge.Cuts.gbr", std::ios::trunc)
      << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Profile,NP*%\n%ADD10C,0.100000*%\nM02*\n";
  const ToolRun r = run("board " + dir + " -o " + dir + "/out --json --no-plot");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["cutout_length_mm"], 0.0);
  EXPECT_EQ(j["holes"], 3);
  EXPECT_NE(r.err.find("t-Edge.Cuts.gbr: the outline layer draws nothing: planned without a "
                       "cut-out"),
            std::string::npos)
      << r.err;
  ASSERT_EQ(j["notes"].size(), 1u);
}

// The file's X2 file function comes before its name, and every file read says what it was
// taken for and why.
TEST(BoardCli, AFoldersFilesSayWhatTheyWereTakenFor) {
  const std::string dir = write_board("taken-for");
  // A name that says bottom copper, a file function that says top: the file function wins.
  std::filesystem::rename(dir + "/t-F.Cu.gbr", dir + "/t_Bottom.gbr");
  const ToolRun r = run("board " + dir + " -o " + dir + "/out --json --no-plot");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["side"], "top");
  EXPECT_NE(r.err.find("t_Bottom.gbr: taken as copper top (from its X2 file function)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("t-PTH.drl: taken as drill (from its name)"), std::string::npos) << r.err;
}

// The file function is read wherever the header puts it: after 6 KiB of comments (a long
// licence or a tool's settings) it still says top copper (outside tester: only the first
// 4 KiB were looked at, and the file was left out for a name that says nothing).
TEST(BoardCli, AnX2FileFunctionAfterALongHeaderIsRead) {
  std::string top = kTopCopper;
  top.replace(top.find("%EXTRA%"), 7, "");
  // Then 6 KiB, and so that the attribute straddles the first 4 KiB (outside tester 24: cut
  // there, it was read as no file function, and a name that says bottom won).
  const size_t at = top.find("%TF.FileFunction");
  for (const size_t before : {size_t{6 * 1024}, size_t{4096 - 20}, size_t{4096 - 4}}) {
    SCOPED_TRACE(before);
    const std::string dir = write_board("late-x2-" + std::to_string(before));
    std::string comments;
    while (at + comments.size() < before) comments += "G04 a long header comment line*\n";
    comments.resize(before - at - 2);
    comments += "*\n";
    std::string late = top;
    late.replace(at, 0, comments);
    ASSERT_EQ(late.find("%TF.FileFunction"), before);
    std::filesystem::remove(dir + "/t-F.Cu.gbr");
    std::ofstream(dir + "/copper-B.Cu.gbr") << late;  // the name says bottom
    const ToolRun r = run("board " + dir + " -o " + dir + "/out --json --no-plot");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["side"], "top");
    EXPECT_NE(r.err.find("copper-B.Cu.gbr: taken as copper top (from its X2 file function)"),
              std::string::npos)
        << r.err;
  }
}

// A bottom-side job's outputs are named after the bottom copper, not the first file given.
TEST(BoardCli, ABottomJobIsNamedAfterItsBottomCopper) {
  const std::string dir = write_board("bottom-name");
  std::string bottom = kTopCopper;
  bottom.replace(bottom.find("%EXTRA%"), 7, "");
  bottom.replace(bottom.find("Copper,L1,Top"), 13, "Copper,L2,Bot");
  std::ofstream(dir + "/back.gbl") << bottom;
  const ToolRun r = run("board --top " + dir + "/t-F.Cu.gbr --bottom " + dir +
                        "/back.gbl --side bottom -o " + dir + "/out --no-plot");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/back.board.json"));
}

// `run` (and `send`, which plans the same way) on PCB files plans the job that `board` showed:
// the board's feed and margin where none is given, the given ones where they are.
TEST(BoardCli, RunPlansTheBoardThatTheBoardCommandShowed) {
  const std::string dir = write_board("same");
  auto board_json = [&](const std::string& options) {
    const ToolRun b = run("board " + dir + " -o " + dir + "/out --json --no-check " + options);
    EXPECT_EQ(b.code, 0) << b.err;
    return nlohmann::json::parse(b.out);
  };
  auto run_json = [&](const std::string& options) {
    const ToolRun r = run("run " + dir + " -o " + dir + "/run --cut-step 1.8 " + options);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(
        std::ifstream(dir + "/run/" + std::to_string(getpid()) + "-same.json"));
  };
  for (const std::string options : {"", "--feed 8 --margin 12"}) {
    const nlohmann::json b = board_json(options + " --cut-step 1.8");
    const nlohmann::json r = run_json(options + (options.empty() ? "" : " --tol 0.004"));
    EXPECT_NEAR(r["planned_cut_mm"].get<double>(), b["cut_length_mm"].get<double>(), 1e-9)
        << options;
    // The margin moves the board, and so the rapids from the zero to it and back.
    EXPECT_NEAR(r["planned_rapid_mm"].get<double>(), b["rapid_length_mm"].get<double>(), 1e-9)
        << options;
    EXPECT_EQ(r["feed_mm_per_s"].get<double>(), options.empty() ? 5.0 : 8.0);
    // The controller's chords come out of the isolation clearance: 1 um unless given.
    EXPECT_EQ(r["chord_tolerance_mm"].get<double>(), options.empty() ? 0.001 : 0.004);
  }
}

// An option of the other kind of input is refused, not ignored: a board is cut at its own
// size and depths, a drawing has no copper to isolate.
TEST(BoardCli, OptionsForTheOtherKindOfInputAreRefused) {
  const std::string dir = write_board("options");
  const ToolRun scaled = run("run " + dir + " -o " + dir + "/out --scale 2");
  EXPECT_EQ(scaled.code, 2) << scaled.err;
  EXPECT_NE(scaled.err.find("--scale is for drawings (DXF, G-code), not PCB files"),
            std::string::npos)
      << scaled.err;
  const std::string dxf = dir + "/line.dxf";
  std::ofstream(dxf) << "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n1\n20\n1\n11\n9\n21\n1\n"
                        "0\nENDSEC\n0\nEOF\n";
  const ToolRun widened = run("run " + dxf + " -o " + dir + "/out --tool-width 0.1");
  EXPECT_EQ(widened.code, 2) << widened.err;
  EXPECT_NE(widened.err.find("--tool-width is for PCB files"), std::string::npos) << widened.err;
  const ToolRun plain = run("run " + dxf + " -o " + dir + "/out --scale 2");
  EXPECT_EQ(plain.code, 0) << plain.err;
}

// In a folder, a Gerber whose name says nothing is read when its X2 file function names the
// layer, and left out with a way to name it when nothing does.
TEST(BoardCli, AFoldersGerberWithAPlainNameIsReadByItsX2FileFunction) {
  const std::string dir = write_board("x2");
  std::filesystem::rename(dir + "/t-F.Cu.gbr", dir + "/layer1.gbr");  // X2: Copper,L1,Top
  std::ofstream(dir + "/notes.gbr") << "%FSLAX46Y46*%\n%MOMM*%\nM02*\n";
  const ToolRun r = run("board " + dir + " -o " + dir + "/out --json --no-check --no-plot");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["islands"], 2);
  EXPECT_NE(r.err.find("layer1.gbr: taken as copper top (from its X2 file function)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("notes.gbr: neither its name nor an X2 file function says copper"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("name it with --top, --bottom or --outline"), std::string::npos) << r.err;
}

// A copper file that neither X2 nor its name identifies (Eagle writes .gbx): refused with
// the ways to name it, and run as copper with a "top:" prefix.
TEST(BoardCli, ACopperFileWithoutAKnownNameIsNamedByItsSidePrefix) {
  const std::string dir = write_board("anon");
  std::string top = kTopCopper;
  top.replace(top.find("%TF.FileFunction,Copper,L1,Top*%\n"), 33, "");
  top.replace(top.find("%EXTRA%"), 7, "");
  const std::string file = dir + "/copper.gbx";
  std::ofstream(file) << top;
  const ToolRun refused = run("run " + file + " -o " + dir + "/out");
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(refused.err.find("copper.gbx: cannot tell which layer this is"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("or give copper as top:FILE or bottom:FILE"), std::string::npos);
  const ToolRun r = run("run top:" + file + " -o " + dir + "/out");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("copper.gbx: taken as top copper (from the 'top:' prefix)"),
            std::string::npos)
      << r.err;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/out/copper.json"));
  EXPECT_EQ(j["outcome"], "completed");
}

TEST(BoardCli, AnUnreadableGerberIsAnInputError) {
  const std::string dir = write_board("bad", "D99*\nX1000000Y1000000D03*\n");  // no D99
  const ToolRun r = run("board " + dir + " -o " + dir + "/out");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("t-F.Cu.gbr"), std::string::npos) << r.err;
}

TEST(BoardCli, OnlyTheJobSidesCopperIsRead) {
  // The bottom copper is broken: a top-side job does not read it (it says so), a bottom-side
  // job does and stops at its error.
  const std::string dir = write_board("sides");
  std::ofstream(dir + "/t-B.Cu.gbr") << "%FSLAX46Y46*%\n%MOMM*%\nD99*\nX0Y0D03*\nM02*\n";
  for (const std::string side : {"", " --side top"}) {
    const ToolRun top = run("board " + dir + side + " -o " + dir + "/out --no-plot --json");
    EXPECT_EQ(top.code, 0) << side << top.err;
    EXPECT_NE(top.err.find("t-B.Cu.gbr: copper of the other side: not read for this job"),
              std::string::npos)
        << top.err;
  }
  const ToolRun bottom = run("board " + dir + " --side bottom -o " + dir + "/out --no-plot");
  EXPECT_EQ(bottom.code, 2) << bottom.out;
  EXPECT_NE(bottom.err.find("t-B.Cu.gbr:3: D99"), std::string::npos) << bottom.err;
}

TEST(BoardCli, FilesNamedByOptionAreReadAsThatLayerWhateverTheirNames) {
  // An Excellon file with a name no tool knows (holes.txt) given as --drill is drilled; a
  // missing one is named with the reason.
  const std::string dir = write_board("named");
  std::ofstream(dir + "/holes.txt") << kDrillInch;
  const ToolRun r = run("board --top " + dir + "/t-F.Cu.gbr --drill " + dir + "/holes.txt -o " +
                        dir + "/out --no-plot --no-check --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["holes"], 3);
  const ToolRun missing = run("board --top " + dir + "/t-F.Cu.gbr --drill " + dir +
                              "/nowhere.txt -o " + dir + "/out --no-plot");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("nowhere.txt: cannot open the file"), std::string::npos)
      << missing.err;
}

TEST(BoardCli, TwoFilesForOneCopperLayerAreAnInputErrorNamingBoth) {
  const std::string dir = write_board("twice");
  std::ofstream(dir + "/u-F.Cu.gbr")
      << std::string(kTopCopper).replace(std::string(kTopCopper).find("%EXTRA%"), 7, "");
  const ToolRun r = run("board " + dir + " -o " + dir + "/out");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("two files for the top copper"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("t-F.Cu.gbr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("u-F.Cu.gbr"), std::string::npos) << r.err;
}

// The guide's first board examples that name the shared samples run as printed (exit 0),
// and the shipped example_board's refusal at the default tool names the width that plans it
// and the option to plan anyway (a user meets that refusal first).
TEST(BoardCli, TheGuidesFirstBoardExamplesRunAsPrinted) {
  const std::string shared = std::string(ENGRAVER_SOURCE_DIR) + "/../shared";
  if (!std::filesystem::is_directory(shared + "/samples/pcb/example_board"))
    GTEST_SKIP() << shared << " (shared samples) absent";
  std::ifstream guide(std::string(ENGRAVER_SOURCE_DIR) + "/docs/user-guide.md");
  ASSERT_TRUE(guide);
  std::string line;
  while (std::getline(guide, line) && line.rfind("## PCB boards: `engraver board`", 0) != 0) {
  }
  std::vector<std::string> examples;  // the first indented block after the heading
  bool in_block = false;
  while (std::getline(guide, line)) {
    if (line.rfind("    engraver ", 0) == 0) {
      in_block = true;
      if (line.find("../shared/") != std::string::npos &&
          (line.rfind("    engraver board ", 0) == 0 || line.rfind("    engraver run ", 0) == 0))
        examples.push_back(line.substr(std::string("    engraver ").size()));
    } else if (in_block) {
      break;
    }
  }
  ASSERT_EQ(examples.size(), 2u) << "the guide's board and run examples on the shared samples";
  const std::string out = testing::TempDir() + "/" + std::to_string(getpid()) + "-guide";
  for (std::string args : examples) {
    const size_t at = args.find("../shared");
    args.replace(at, std::string("../shared").size(), shared);
    const size_t o = args.find(" -o out");
    ASSERT_NE(o, std::string::npos) << args;
    args.replace(o, std::string(" -o out").size(), " -o " + out);
    const ToolRun r = run(args);
    EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
  }
  const std::string example = "board " + shared + "/samples/pcb/example_board --no-plot -o " + out;
  const ToolRun refused = run(example);
  EXPECT_EQ(refused.code, 1) << refused.err;
  EXPECT_NE(refused.err.find("Use a narrower tool: --tool-width 0.041 passes every gap (the "
                             "narrowest, 0.057 mm, less 2 x 0.008 mm clearance), or plan anyway "
                             "(--allow-narrow-gaps: the copper at those gaps stays joined).\n"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(run(example + " --tool-width 0.041").code, 0);
  // The guide's gap printed with the digits that tell it from the tool, and the clearance
  // that passes with a tool that fits the gap.
  EXPECT_NE(run(example + " --tool-width 0.0574 --clearance 0")
                .err.find("gap 0.0571 mm < tool 0.0574 mm"),
            std::string::npos);
  EXPECT_NE(run(example + " --tool-width 0.05 --clearance 0.004")
                .err.find("Or keep the tool and lower the clearance: --clearance 0.003 passes "
                          "every gap (the clearance is the room kept between the tool's edge and "
                          "the copper for the curve fit and the machine's contour error; with "
                          "less, the checks may find the tool in the copper).\n"),
            std::string::npos);
  EXPECT_EQ(run(example + " --tool-width 0.05 --clearance 0.003").code, 0);
  std::filesystem::remove_all(out);
}

}  // namespace
