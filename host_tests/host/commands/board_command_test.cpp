// `engraver board`, the PCB input of `points` and the shared board-options resolver as
// functions, called directly on a small board written here: two pads joined by a track and a
// square pad, a drill file in inches with two sizes, and an outline drawn as strokes.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>  // temp_directory_path, exists
#include <fstream>     // std::ofstream, std::ifstream
#include <iterator>    // std::istreambuf_iterator

#include "host/lib/commands/board_command.h"
#include "host/lib/commands/exit_codes.h"
#include "host/lib/pcb/board_args.h"

namespace host::commands {
namespace {

namespace fs = std::filesystem;

const char* kTopCopper =
    "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n"
    "%ADD10C,1.600000*%\n%ADD11C,0.300000*%\n%ADD12R,2.000000X2.000000*%\n"
    "D10*\nX10000000Y10000000D03*\nX20000000Y10000000D03*\n"
    "D11*\nX10000000Y10000000D02*\nX20000000Y10000000D01*\n"
    "D12*\nX25000000Y15000000D03*\nM02*\n";

const char* kDrillInch =
    "M48\nINCH\nT1C0.0315\nT2C0.0394\n%\nG90\nG05\nT1\nX0.393701Y0.393701\n"
    "X0.787402Y0.393701\nT2\nX0.984252Y0.590551\nM30\n";

const char* kOutline =
    "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Profile,NP*%\n%ADD10C,0.100000*%\nD10*\n"
    "X0Y0D02*\nX35000000Y0D01*\nX35000000Y25000000D01*\nX0Y25000000D01*\nX0Y0D01*\nM02*\n";

// A folder holding the board, named `name` (the board's name).
std::string write_board(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("board_command_test-" + std::to_string(getpid())) / name;
  fs::create_directories(dir);
  std::ofstream(dir / "t-F.Cu.gbr") << kTopCopper;
  std::ofstream(dir / "t-PTH.drl") << kDrillInch;
  std::ofstream(dir / "t-Edge.Cuts.gbr") << kOutline;
  return dir.string();
}

struct Log {
  std::vector<std::string> lines;
  CommandLog log() {
    return [this](const std::string& l) { lines.push_back(l); };
  }
};

TEST(BoardCommand, PlansChecksReportsAndWritesAWholeBoard) {
  const std::string dir = write_board("ok");
  BoardCommandOptions o;
  o.files = {dir};
  o.outdir = dir + "/out";
  Log log;
  BoardResult r = run_board(o, log.log());
  EXPECT_EQ(r.name, "ok");
  EXPECT_EQ(r.job.report.islands, 2u);
  EXPECT_EQ(r.job.report.holes, 3u);
  EXPECT_EQ(r.job.report.holes_on_copper, 3u);  // the inch drill file lines up with the copper
  EXPECT_EQ(r.job.report.tool_changes, 3);      // drill 0.8, drill 1.0, cutter
  ASSERT_TRUE(r.check.has_value());
  EXPECT_TRUE(r.check->hits.empty());
  EXPECT_TRUE(r.check_ok);
  ASSERT_EQ(r.tool_bytes.size(), 4u);
  for (size_t b : r.tool_bytes) EXPECT_GT(b, 0u);
  EXPECT_NO_THROW(refuse_failed_board(r));
  // Folder files read by their X2 attributes or names, said in the log.
  EXPECT_FALSE(log.lines.empty());
  // The byte comparison for the performance page only when asked for.
  EXPECT_FALSE(r.wire.has_value());
  const nlohmann::json j = board_report_json(o, r);
  EXPECT_FALSE(j.contains("isolation_spline_bytes"));
  EXPECT_EQ(j["board"], "ok");
  EXPECT_EQ(j["side"], "top");
  EXPECT_EQ(j["check"]["copper_hits"], 0);
  EXPECT_EQ(j["check"]["passed"], true);
  EXPECT_EQ(j["bytes_per_tool"][3]["name"], "Cutter 1.00mm");
  write_board_outputs(o, j, &r);
  EXPECT_EQ(r.base, (fs::path(o.outdir) / "ok").string());
  for (const char* ext : {".board.json", ".board.svg"})
    EXPECT_TRUE(fs::exists(r.base + ext)) << ext;
  EXPECT_FALSE(fs::exists(r.base + ".board.png"));  // only with o.png (--png)
  const std::string text = board_report_text(o, r);
  EXPECT_NE(text.find("ok: top side, first tool V-bit 0.20mm"), std::string::npos) << text;
  EXPECT_EQ(text.find("as splines"), std::string::npos) << text;
  EXPECT_NE(text.find("report: " + r.base + ".board.json"), std::string::npos) << text;
  // The check's outcome is in the summary when it passes, and says when it was skipped.
  EXPECT_NE(text.find("\n  check: passed: no copper cut, 2 islands each cut free (to 0.003 mm)\n"),
            std::string::npos)
      << text;
  o.check = false;
  const BoardResult unchecked = run_board(o, log.log());
  EXPECT_FALSE(unchecked.check.has_value());
  EXPECT_NE(board_report_text(o, unchecked).find("\n  check: skipped (--no-check)\n"),
            std::string::npos)
      << board_report_text(o, unchecked);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A board without an outline has no cut-out: the report says so once (not "0.0 mm per pass,
// 0 tabs") and the plot's legend names no cut-out or tabs; with an outline it names both.
TEST(BoardCommand, ABoardWithoutAnOutlineSaysNoCutOutAndItsLegendShowsNone) {
  const std::string dir = write_board("no-outline");
  fs::remove(fs::path(dir) / "t-Edge.Cuts.gbr");
  BoardCommandOptions o;
  o.files = {dir};
  o.outdir = dir + "/out";
  o.check = false;
  Log log;
  BoardResult r = run_board(o, log.log());
  EXPECT_EQ(r.job.report.no_cutout, "no outline layer");
  EXPECT_EQ(board_report_json(o, r)["no_cutout"], "no outline layer");  // the JSON says why too
  const std::string text = board_report_text(o, r);
  EXPECT_NE(text.find("\n  no cut-out: no outline layer; 2 tool changes\n"), std::string::npos)
      << text;
  EXPECT_EQ(text.find("\n  cut-out:"), std::string::npos) << text;
  EXPECT_EQ(text.find("tabs"), std::string::npos) << text;
  write_board_outputs(o, board_report_json(o, r), &r);
  const std::string svg = read_file(r.base + ".board.svg");
  EXPECT_NE(svg.find(">holes</text>"), std::string::npos);
  EXPECT_EQ(svg.find("cut-out"), std::string::npos);
  EXPECT_EQ(svg.find(">tabs</text>"), std::string::npos);

  const std::string with_outline = write_board("with-outline");
  o.files = {with_outline};
  o.outdir = with_outline + "/out";
  BoardResult cut = run_board(o, log.log());
  EXPECT_EQ(cut.job.report.no_cutout, "");
  EXPECT_EQ(board_report_json(o, cut)["no_cutout"], "");
  EXPECT_NE(
      board_report_text(o, cut).find("\n  cut-out: 123.1 mm per pass, 4 tabs; 3 tool changes\n"),
      std::string::npos)
      << board_report_text(o, cut);
  write_board_outputs(o, board_report_json(o, cut), &cut);
  const std::string cut_svg = read_file(cut.base + ".board.svg");
  EXPECT_NE(cut_svg.find(">cut-out (cutter width)</text>"), std::string::npos);
  EXPECT_NE(cut_svg.find(">tabs</text>"), std::string::npos);
}

TEST(BoardCommand, WireBytesCompareTheIsolationsEncodingsWhenAsked) {
  BoardCommandOptions o;
  o.files = {write_board("wire")};
  o.wire_bytes = true;
  o.check = false;
  Log log;
  const BoardResult r = run_board(o, log.log());
  ASSERT_TRUE(r.wire.has_value());
  EXPECT_FALSE(r.check.has_value());
  EXPECT_GT(r.wire->spline_frames, 0u);
  EXPECT_LT(r.wire->spline_bytes, r.wire->g1_bytes);
  EXPECT_LT(r.wire->spline_bytes, r.wire->spline_bytes_full);
  const nlohmann::json j = board_report_json(o, r);
  EXPECT_EQ(j["isolation_spline_bytes"], r.wire->spline_bytes);
  EXPECT_NE(board_report_text(o, r).find("as splines"), std::string::npos);
}

TEST(BoardCommand, NamedLayersAreTheirKindAndBadOptionsAreUsageErrors) {
  const std::string dir = write_board("named");
  BoardCommandOptions o;
  o.bottom = dir + "/t-F.Cu.gbr";  // top copper by its attributes, bottom by the option
  o.drills = {dir + "/t-PTH.drl"};
  Log log;
  const BoardResult r = plan_board_command(o, log.log());
  EXPECT_EQ(r.options.side, pcb::BoardSide::kBottom);  // only bottom copper given
  EXPECT_EQ(r.name, "t-F.Cu");
  o.board.side = "top";  // no top copper: nothing to isolate
  try {
    plan_board_command(o, log.log());
    FAIL() << "planned the top side without top copper";
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitUsage);
    EXPECT_NE(std::string(e.what()).find("give --side bottom"), std::string::npos) << e.what();
  }
}

TEST(BoardPoints, ToolPathsOfTheBoardInTheFilesFrame) {
  Log log;
  const BoardPoints p = board_points(write_board("points"), pcb::BoardArgs(), 0.005, log.log());
  ASSERT_FALSE(p.paths.empty());
  EXPECT_EQ(p.paths.front().tool, 0u);  // the V-bit first
  EXPECT_LT(p.paths.front().z_um, 0);
  size_t holes = 0;
  for (const BoardToolPath& t : p.paths) {
    ASSERT_LT(t.tool, p.job.tools.size());
    if (t.points_file_mm.size() == 1) ++holes;
    for (const Point2& pt : t.points_file_mm) {  // the files' frame: on the 35 x 25 mm board
      EXPECT_GT(pt.x(), -3.0);
      EXPECT_LT(pt.x(), 38.0);
    }
  }
  EXPECT_EQ(holes, 3u);
}

TEST(BoardArgs, OneResolverSaysTheSideAndRefusesWhatCannotPlan) {
  pcb::BoardFileSet bottom_only;
  pcb::PcbLayer copper;
  copper.kind = pcb::LayerKind::kCopperBottom;
  copper.path = "b.gbr";
  bottom_only.add(copper);
  pcb::BoardArgs a;
  pcb::BoardMachine m;
  m.margin_mm = 7;
  a.isolation.tool_width_mm = 0.3;
  pcb::BoardOptions o = pcb::resolve_board_options(a, m, bottom_only, "");
  EXPECT_EQ(o.side, pcb::BoardSide::kBottom);
  EXPECT_DOUBLE_EQ(o.isolation.tool_width_mm, 0.3);
  EXPECT_DOUBLE_EQ(o.margin_mm, 7);
  EXPECT_THROW(pcb::resolve_board_options(a, m, bottom_only, "top"), pcb::BoardArgsError);
  a.side = "left";
  EXPECT_THROW(pcb::resolve_board_options(a, m, bottom_only, ""), pcb::BoardArgsError);
  a.side.clear();
  a.isolation.clearing_tool_mm = 0.6;
  a.isolation.passes = 2;
  a.isolation.narrow_passes = 2;
  EXPECT_THROW(pcb::resolve_board_options(a, m, bottom_only, ""), pcb::BoardArgsError);
  a.isolation.passes = 3;
  a.alignment.holes = "1,2;3";
  EXPECT_THROW(pcb::resolve_board_options(a, m, bottom_only, ""), pcb::BoardArgsError);
  a.alignment.holes = "1,2;3,4";
  o = pcb::resolve_board_options(a, m, bottom_only, "");
  ASSERT_EQ(o.alignment.holes_file_mm.size(), 2u);
  EXPECT_DOUBLE_EQ(o.alignment.holes_file_mm[1].y(), 4);
  a.alignment.holes.clear();
  a.alignment.measured_mm = {1, 2, 3, 4};
  EXPECT_THROW(pcb::resolve_board_options(a, m, bottom_only, ""), pcb::BoardArgsError);
}

// The words for a side and the side of the copper given: what the CLI's --side check, the
// resolver and the server's settings all ask.
TEST(BoardArgs, TheSideWordsAndTheSideOfTheCopperGiven) {
  EXPECT_TRUE(pcb::is_board_side("top"));
  EXPECT_TRUE(pcb::is_board_side("bottom"));
  for (const char* word : {"", "Top", "left", "top ", "bot"})
    EXPECT_FALSE(pcb::is_board_side(word));
  pcb::BoardFileSet none, bottom_only, both;
  pcb::PcbLayer copper;
  copper.kind = pcb::LayerKind::kCopperBottom;
  copper.path = "b.gbr";
  bottom_only.add(copper);
  both.add(copper);
  copper.kind = pcb::LayerKind::kCopperTop;
  copper.path = "t.gbr";
  both.add(copper);
  EXPECT_EQ(pcb::side_of_copper(none), "top");
  EXPECT_EQ(pcb::side_of_copper(bottom_only), "bottom");
  EXPECT_EQ(pcb::side_of_copper(both), "top");
}

}  // namespace
}  // namespace host::commands
