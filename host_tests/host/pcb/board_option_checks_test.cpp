// The board options' checks as a user meets them (issue 24, an outside tester's findings):
// numbers that are not finite, copper of the other side only, a measured alignment that
// moves the job off the work area, and options that would otherwise be silently ignored.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <fmt/format.h>  // fmt::format

#include <cmath>  // std::cos, std::sin
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "host/cli/option_ranges.h"
#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::ToolRun;

ToolRun run(const std::string& args) {
  return host_tests::run_tool(ENGRAVER_EXE, args);
}

// Two pads joined by a track on either side (mm), two holes in them, a 40 x 30 mm outline.
std::string write_board(const std::string& name) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-opt-" + name;
  std::filesystem::create_directories(dir);
  for (const std::string side : {"F.Cu", "B.Cu"})
    std::ofstream(dir + "/b-" + side + ".gbr")
        << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,"
        << (side == "F.Cu" ? "L1,Top" : "L2,Bot")
        << "*%\n%ADD10C,1.600000*%\n%ADD11C,0.300000*%\n"
           "D10*\nX10000000Y10000000D03*\nX30000000Y20000000D03*\n"
           "D11*\nX10000000Y10000000D02*\nX30000000Y20000000D01*\nM02*\n";
  std::ofstream(dir + "/b-PTH.drl")
      << "M48\nMETRIC\nT1C0.800\n%\nG90\nG05\nT1\nX10.0Y10.0\nX30.0Y20.0\nM30\n";
  std::ofstream(dir + "/b-Edge.Cuts.gbr")
      << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Profile,NP*%\n%ADD10C,0.100000*%\nD10*\n"
         "X0Y0D02*\nX40000000Y0D01*\nX40000000Y30000000D01*\nX0Y30000000D01*\nX0Y0D01*\nM02*\n";
  return dir;
}

// "nan" and "inf" parse as numbers and pass every range check (comparisons with NaN are
// false): they were planned with and refused later as a failed job (exit 1), or not at all.
TEST(BoardOptionChecks, NumbersThatAreNotFiniteAreBadInputNamingTheOption) {
  const std::string dir = write_board("nan");
  const std::string out = " -o " + dir + "/out";
  struct Case {
    std::string args, option, value;
  };
  const Case cases[] = {
      {"board " + dir + " --tool-width nan" + out, "--tool-width", "nan"},
      {"board " + dir + " --depth inf" + out, "--depth", "inf"},
      {"board " + dir + " --tab-width -inf" + out, "--tab-width", "-inf"},
      {"board " + dir + " --work nan 200" + out, "--work", "nan"},
      {"board " + dir + " --feed NaN" + out, "--feed", "NaN"},
      {"board " + dir + " --align-holes auto --align-measured 1 2 nan 4" + out, "--align-measured",
       "nan"},
      {"run " + dir + " --cut-depth inf" + out, "--cut-depth", "inf"},
      {"points " + dir + " --overlap nan", "--overlap", "nan"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.option + ": '" + c.value + "' is not a finite number"),
              std::string::npos)
        << c.args << "\n"
        << r.err;
  }
}

// Only bottom copper with --side top (or the reverse) planned holes and cut-out alone, exit 0.
TEST(BoardOptionChecks, CopperOfTheOtherSideOnlyIsRefusedNotPlannedEmpty) {
  const std::string dir = write_board("side");
  const std::string files = " --drill " + dir + "/b-PTH.drl --outline " + dir + "/b-Edge.Cuts.gbr";
  for (const std::string& command :
       {"board --top " + dir + "/b-F.Cu.gbr" + files + " --side bottom -o " + dir + "/out",
        "board --bottom " + dir + "/b-F.Cu.gbr" + files + " --side top -o " + dir + "/out",
        "run top:" + dir + "/b-F.Cu.gbr," + dir + "/b-PTH.drl --side bottom -o " + dir + "/out",
        "points top:" + dir + "/b-F.Cu.gbr," + dir + "/b-PTH.drl --side bottom"}) {
    const ToolRun r = run(command);
    EXPECT_EQ(r.code, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("copper: nothing to isolate; give --side "), std::string::npos)
        << command << "\n"
        << r.err;
  }
  // The side whose copper is given plans.
  EXPECT_EQ(run("board --bottom " + dir + "/b-F.Cu.gbr" + files + " -o " + dir + "/out").code, 0);
}

// The alignment holes of the bottom job (machine mm, hole 1 first).
std::vector<double> nominal_holes(const std::string& dir) {
  const ToolRun r =
      run("board " + dir + " --side bottom --align-holes auto --json --no-plot -o " + dir + "/out");
  EXPECT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& h = j["alignment"]["holes_mm"];
  return {h[0][0].get<double>(), h[0][1].get<double>(), h[1][0].get<double>(),
          h[1][1].get<double>()};
}

// The measured holes for a blank shifted by (dx, dy) and turned by deg about hole 1.
std::string measured(const std::vector<double>& h, double dx, double dy, double deg) {
  const double a = deg * M_PI / 180, vx = h[2] - h[0], vy = h[3] - h[1];
  const double x1 = h[0] + dx, y1 = h[1] + dy;
  return std::to_string(x1) + " " + std::to_string(y1) + " " +
         std::to_string(x1 + std::cos(a) * vx - std::sin(a) * vy) + " " +
         std::to_string(y1 + std::sin(a) * vx + std::cos(a) * vy);
}

// The work area was checked on the job before it was turned and shifted onto the measured
// holes: a blank measured off the table planned and ran (exit 0).
TEST(BoardOptionChecks, AMeasuredAlignmentThatMovesTheJobOffTheWorkAreaIsRefusedEverywhere) {
  const std::string dir = write_board("placed");
  const std::vector<double> h = nominal_holes(dir);
  ASSERT_EQ(h.size(), 4u);
  const std::string off =
      " --side bottom --align-holes auto --align-measured " + measured(h, 280, 0, 0);
  for (const std::string& command :
       {"board " + dir + off + " -o " + dir + "/out", "run " + dir + off + " -o " + dir + "/out",
        "points " + dir + off}) {
    const ToolRun r = run(command);
    EXPECT_EQ(r.code, 1) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("turned and shifted onto the measured alignment holes, the board job "
                         "spans ("),
              std::string::npos)
        << command << "\n"
        << r.err;
    EXPECT_NE(r.err.find("but the work area is (0, 0) .. (297.0, 210.0) mm"), std::string::npos)
        << r.err;
  }
  // The cut-out's cutter reaches 6 mm from x = 0 (the 5 mm margin and 1 mm of the outline's
  // clearance for the pins): 5.5 mm to the left fits unturned; turned 3 degrees about hole 1,
  // the board's upper left corner, 35 mm above it, reaches 1.8 mm further left, beyond x = 0:
  // the turn itself is checked.
  const std::string board =
      "board " + dir + " --side bottom --align-holes auto --no-plot -o " + dir + "/out";
  EXPECT_EQ(run(board + " --align-measured " + measured(h, -5.5, 0, 0)).code, 0);
  const ToolRun turned = run(board + " --align-measured " + measured(h, -5.5, 0, 3));
  EXPECT_EQ(turned.code, 1) << turned.err;
  EXPECT_NE(turned.err.find("spans (-"), std::string::npos) << turned.err;
}

// Options that did nothing in these combinations, without a word.
TEST(BoardOptionChecks, OptionsThatWouldBeIgnoredAreRefused) {
  const std::string dir = write_board("ignored");
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out ";
  struct Case {
    std::string args;
    int code;
    std::string says;
  };
  const Case cases[] = {
      // The clearing tool cuts the passes beyond the narrow ones: with one pass, none.
      {board + "--clearing-tool 0.8", 2, "--clearing-tool cuts the passes beyond"},
      {board + "--clearing-tool 0.8 --passes 3 --narrow-passes 3", 2,
       "--clearing-tool cuts the passes beyond --narrow-passes (3), but --passes is 3"},
      {board + "--narrow-passes 2", 2, "--narrow-passes requires --clearing-tool"},
      {board + "--narrow-passes 2 --clearing-tool 0", 2,
       "--narrow-passes counts the isolation tool's passes"},
      {"run " + dir + " --pins-only -o " + dir + "/out", 2, "--pins-only requires --blank-error"},
      {board + "--align-holes ''", 2, "--align-holes: empty: say auto"},
      // The same hole twice, and a hole overlapping its own mirror image (axis x = 20).
      {board + "--align-holes '10,-20;10,-20'", 1, "overlap: holes of 3.00 mm"},
      {board + "--align-holes '19,-20'", 1, "overlap: holes of 3.00 mm"},
      // One hole on the flip axis is one hole: no second to measure (was an internal error).
      {board + "--align-holes '20,-20' --align-measured 1 2 3 4", 2,
       "--align-measured needs two alignment holes"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(c.args);
    EXPECT_EQ(r.code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
  }
  // What they are for still plans.
  EXPECT_EQ(run(board + "--clearing-tool 0.8 --passes 4 --narrow-passes 2").code, 0);
  EXPECT_EQ(run(board + "--align-holes '10,-20'").code, 0);
}

// ---- One range per option, the same in every command (issue 24, F4) ----

using host::cli::option_ranges;
using host::cli::OptionRange;

std::string bound(double v) {
  return fmt::format("{:g}", v);
}

// Just outside a bound: a whole step for a count, a thousandth of the range otherwise.
std::string outside(const OptionRange& r, bool below) {
  const double step = r.integer ? 1.0 : (r.max - r.min) * 1e-3;
  return bound(below ? r.min - step : r.max + step);
}

std::string values(const OptionRange& r, const std::string& v) {
  const std::string o = r.option;
  const int n = o == "--work" || o == "--offset" || o == "--probe-grid" ? 2
                : o == "--align-measured"                               ? 4
                                                                        : 1;
  std::string out;
  for (int k = 0; k < n; ++k) out += " " + v;
  return out;
}

// Every bound of the table is allowed, and a step beyond it is not.
TEST(BoardOptionRanges, EveryBoundOfTheTableIsInsideAndAStepBeyondIsOutside) {
  for (const OptionRange& r : option_ranges()) {
    EXPECT_LT(r.min, r.max) << r.option;
    EXPECT_EQ(host::cli::range_refusal(r, bound(r.min)), "") << r.option;
    EXPECT_EQ(host::cli::range_refusal(r, bound(r.max)), "") << r.option;
    for (const bool below : {true, false}) {
      const std::string v = outside(r, below);
      EXPECT_EQ(host::cli::range_refusal(r, v),
                v + " is outside the allowed range " + bound(r.min) + " .. " + bound(r.max) +
                    (*r.unit ? std::string(" ") + r.unit : std::string()))
          << r.option;
    }
  }
}

// The commands that take an option of the table: the board options are in all five, but the
// machine's (--feed, --z-up, --margin, --work) not in `points`; the others as listed.
std::string commands_taking(const std::string& option) {
  if (option == "--tol") return "board points run send probe";
  if (option == "--feed" || option == "--z-up" || option == "--margin" || option == "--work")
    return "board run send probe";
  for (const char* o :
       {"--scale", "--chain-tol", "--offset", "--tool-radius", "--fit-tol", "--z-down",
        "--probe-spacing", "--probe-grid", "--probe-margin", "--outlier-limit"})
    if (option == o) return "run send probe";
  if (option == "--poll-ms") return "send";
  if (option == "--vbit-angle" || option == "--copper-um") return "run";
  return "board points run send probe";
}

// A walk over the table through the built tool: in every command that takes the option, a
// value a step beyond either bound is a usage error (exit 2) naming the option and its range,
// before any file is read or any link opened (--probe-grid 1 16 was checked only after
// connecting: exit 6 on a dead link).
TEST(BoardOptionRanges, EveryCommandRefusesAValueBeyondEitherBoundNamingTheOption) {
  const std::string dir = write_board("ranges");
  int checked = 0, expected = 0;
  for (const std::string command : {"board", "points", "run", "send", "probe"}) {
    const std::string help = run(command + " --help").out;
    // send and probe: a link nothing listens on (a connection would fail with exit 6).
    const std::string link =
        command == "send" || command == "probe" ? " --to tcp://127.0.0.1:1" : "";
    for (const OptionRange& r : option_ranges()) {
      const bool takes =
          (" " + commands_taking(r.option) + " ").find(" " + command + " ") != std::string::npos;
      expected += takes;
      EXPECT_EQ(help.find(std::string("  ") + r.option + " ") != std::string::npos, takes)
          << command << " " << r.option;
      if (!takes) continue;
      ++checked;
      // The range as the help shows it.
      EXPECT_NE(help.find(std::string(r.option) + " " + (r.integer ? "INT" : "FLOAT") + ":in [" +
                          bound(r.min) + " .. " + bound(r.max) + "]"),
                std::string::npos)
          << command << " " << r.option;
      for (const bool below : {true, false}) {
        const std::string v = outside(r, below);
        const std::string args = command + " " + dir + link + " " + r.option + values(r, v);
        const ToolRun t = run(args);
        EXPECT_EQ(t.code, 2) << args << "\n" << t.err;
        EXPECT_NE(t.err.find(std::string(r.option) + ": " + v + " is outside the allowed range " +
                             bound(r.min) + " .. " + bound(r.max)),
                  std::string::npos)
            << args << "\n"
            << t.err;
      }
    }
  }
  EXPECT_EQ(checked, expected);
  EXPECT_GE(checked, 4 * 25 + 21);  // the 25 board options at least
}

// The outside tester's findings: values planned with and refused later as a failed job
// (exit 1) by a message that did not name the option, or accepted.
TEST(BoardOptionRanges, TheTestersValuesAreUsageErrorsNamingTheOption) {
  const std::string dir = write_board("tester");
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out ";
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"--depth 0", "--depth: 0 is outside the allowed range 0.001 .. 5 mm"},
      {"--drill-feed 0", "--drill-feed: 0 is outside the allowed range 0.1 .. 60 mm/s"},
      {"--cut-step 0", "--cut-step: 0 is outside the allowed range 0.01 .. 20 mm"},
      {"--z-up -1", "--z-up: -1 is outside the allowed range 0.1 .. 50 mm"},
      {"--tab-width -5", "--tab-width: -5 is outside the allowed range 0 .. 100 mm"},
      {"--depth 0x1p-3", "--depth: '0x1p-3' is not a decimal number"},
      {"--passes 0x3", "--passes: '0x3' is not a decimal number"},
      // A count out of range as typed, not as rewritten for CLI11 (1000).
      {"--passes 1e3", "--passes: 1e3 is outside the allowed range 1 .. 50\n"},
      {"--tabs 1.0e3", "--tabs: 1.0e3 is outside the allowed range 0 .. 100\n"},
      {"--clearing-tool 0.1 --passes 3",
       "--clearing-tool (0.1 mm) must be wider than --tool-width (0.2 mm)"},
      {"--clearing-tool 0.8 --passes 3 --mill-all",
       "--clearing-tool cannot be combined with --mill-all"},
      {"--tab-height 1.8", "--tab-height (1.8 mm) must be below --cut-depth (1.8 mm)"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(board + c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
  }
  // A plain decimal with an exponent is a decimal.
  EXPECT_EQ(run(board + "--depth 5e-2").code, 0);
}

// Options that cannot go together are refused as the line is read, by board, run and points
// alike: the message comes first, before any note on the files (they came after them).
TEST(BoardOptionRanges, OptionsThatCannotGoTogetherAreRefusedBeforeAnyFileIsRead) {
  const std::string dir = write_board("together");
  const std::string clash = " --clearing-tool 0.8 --mill-all";  // the default --passes too
  for (const std::string command :
       {"board " + dir + clash + " -o " + dir + "/out",
        "run " + dir + clash + " -o " + dir + "/out", "points " + dir + clash}) {
    const ToolRun r = run(command);
    EXPECT_EQ(r.code, 2) << command << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("engraver: --clearing-tool cannot be combined with --mill-all", 0), 0u)
        << command << "\n"
        << r.err;
    EXPECT_EQ(r.out, "") << command;
  }
  // The same folder without the clash is read, and says what it took each file for.
  const ToolRun fine = run("board " + dir + " --no-plot -o " + dir + "/out");
  EXPECT_EQ(fine.code, 0) << fine.err;
  EXPECT_NE(fine.err.find("engraver: note: "), std::string::npos) << fine.err;
}

// The second tester's findings (issue 24, #25's CLI): values accepted and ignored, checked
// only after connecting, or refused in CLI11's words instead of the project's.
TEST(BoardOptionRanges, TheSecondTestersValuesAreUsageErrorsNamingTheOption) {
  const std::string dir = write_board("tester2");
  const std::string word = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";
  const std::string out = " -o " + dir + "/out";
  const std::string dead = " --to tcp://127.0.0.1:1";
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      // Silently ignored (the default grid probed, exit 0).
      {"run " + word + " --surface tilt=0.1mm --probe --probe-grid 0 0" + out,
       "--probe-grid: 0 is outside the allowed range 2 .. 16"},
      {"run " + word + " --surface tilt=0.1mm --probe --probe-grid 0 -3" + out,
       "--probe-grid: 0 is outside the allowed range 2 .. 16"},
      // Checked after connecting: exit 6 on a dead link.
      {"send " + word + dead + " --probe --probe-grid 1 16", "--probe-grid: 1 is outside"},
      {"probe " + word + dead + " --probe-grid 4 17", "--probe-grid: 17 is outside"},
      // A hex float in the simulated blank.
      {"run " + word + " --surface tilt=0x1p-3mm" + out,
       "--surface: tilt=0x1p-3mm: '0x1p-3' is not a decimal number"},
      {"run " + word + " --surface bump=10:0x1p3:5mm:50um" + out, "'0x1p3' is not a decimal"},
      // No range: the message overflowed (-9.22337e+15).
      {"run " + word + " --offset 1e300 0" + out,
       "--offset: 1e300 is outside the allowed range -297 .. 297 mm"},
      // CLI11's words ("not in range") before.
      {"run " + word + " --tol 0" + out, "--tol: 0 is outside the allowed range 0.001 .. 1 mm"},
      {"points " + word + " --tol 5", "--tol: 5 is outside the allowed range 0.001 .. 1 mm"},
      {"run " + word + " --scale 0" + out, "--scale: 0 is outside the allowed range 0.001 .. 1000"},
      {"send " + word + dead + " --poll-ms 5000", "--poll-ms: 5000 is outside the allowed range"},
      {"run " + word + " --chain-tol 2" + out,
       "--chain-tol: 2 is outside the allowed range 0 .. 1"},
      {"run " + word + " --tool-radius 11" + out, "--tool-radius: 11 is outside the allowed range"},
      {"run " + word + " --probe-spacing 0.5" + out, "--probe-spacing: 0.5 is outside"},
      {"run " + word + " --probe-margin 51" + out, "--probe-margin: 51 is outside"},
      // CLI11's "Could not convert".
      {"board " + dir + " --passes 1.5" + out, "--passes: '1.5' is not a whole number"},
      {"board " + dir + " --tabs 2.5" + out, "--tabs: '2.5' is not a whole number"},
      // Two ways to say how many tabs: a clash, neither wins.
      {"board " + dir + " --tabs 6 --tab-spacing 30" + out, "--tabs excludes --tab-spacing"},
      {"run " + dir + " --tab-spacing 30 --tabs 2" + out, "--tabs excludes --tab-spacing"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
  }
  // The tab height is checked where tabs are cut only: with no tabs there is none to keep.
  const std::string board = "board " + dir + " --no-plot" + out;
  EXPECT_EQ(run(board + " --tabs 0 --tab-height 1.8").code, 0);
  EXPECT_EQ(run(board + " --tab-width 0 --tab-height 1.8").code, 0);
  EXPECT_EQ(run(board + " --tab-height 1.8").code, 2);
  // A whole number written as 2.0 or 1e0 is that number (it was "Could not convert").
  EXPECT_EQ(run(board + " --tabs 2.0").code, 0) << run(board + " --tabs 2.0").err;
  EXPECT_EQ(run(board + " --passes 1e0").code, 0) << run(board + " --passes 1e0").err;
}

// The narrow-gap refusal said "use a narrower tool" without saying how narrow: the user of the
// shipped example_board (0.057 mm gaps) had to guess. It names the widest tool that passes
// every gap, which plans, while a micrometre more is refused; and the option to plan anyway.
TEST(BoardOptionRanges, TheNarrowGapRefusalNamesTheToolWidthThatPasses) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-opt-narrow";
  std::filesystem::create_directories(dir);
  // Two 1 mm pads 0.1 mm apart.
  std::ofstream(dir + "/gap-F.Cu.gbr")
      << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n%ADD10C,1.000000*%\n"
         "D10*\nX10000000Y10000000D03*\nX11100000Y10000000D03*\nM02*\n";
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out";
  const ToolRun r = run(board);
  EXPECT_EQ(r.code, 1) << r.err;
  const std::string says = "Use a narrower tool: --tool-width ";
  const size_t at = r.err.find(says);
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string width =
      r.err.substr(at + says.size(), r.err.find(' ', at + says.size()) - at - says.size());
  EXPECT_EQ(width, "0.084") << r.err;  // the gap 0.100 mm less 2 x 0.008 mm clearance
  EXPECT_NE(r.err.find(" passes every gap (the narrowest, 0.100 mm, less 2 x 0.008 mm "
                       "clearance), or plan anyway (--allow-narrow-gaps: the copper at those "
                       "gaps stays joined).\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(run(board + " --tool-width " + width).code, 0);
  EXPECT_EQ(run(board + " --tool-width 0.085").code, 1);
  EXPECT_EQ(run(board + " --allow-narrow-gaps").code, 0);
}

// Two 1 mm pads whose edges are `gap_um` apart, alone on a top copper layer.
std::string write_gap_board(const std::string& name, int gap_um) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-opt-" + name;
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/gap-F.Cu.gbr")
      << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n%ADD10C,1.000000*%\n"
      << "D10*\nX10000000Y10000000D03*\nX" << 11000000 + gap_um * 1000 << "Y10000000D03*\nM02*\n";
  return dir;
}

// The narrow-gap refusal read "gap 0.101 mm < tool 0.101 mm": the gap and what the tool
// needs are printed with as many digits as it takes for them to differ, the gap the smaller.
TEST(BoardOptionRanges, TheNarrowGapReadsAsAComparisonThatHolds) {
  const std::string dir = write_gap_board("gapdigits", 100);
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out ";
  for (const std::string& tool :
       {"--tool-width 0.1008 --clearance 0", "--tool-width 0.0998 --clearance 0.0005"}) {
    const ToolRun r = run(board + tool);
    ASSERT_EQ(r.code, 1) << tool << "\n" << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.err, m, std::regex(R"(gap (\S+) mm < (tool )?(\S+) mm)")))
        << r.err;
    EXPECT_NE(m[1].str(), m[3].str()) << r.err;
    EXPECT_LT(std::stod(m[1].str()), std::stod(m[3].str())) << r.err;
  }
  // The tool and clearance as given, not rounded to 0.100 and 0.001.
  EXPECT_NE(run(board + "--tool-width 0.0998 --clearance 0.0005")
                .err.find("(tool 0.0998 mm + 2 x 0.0005 mm clearance)"),
            std::string::npos);
}

// A tool that fits the gap itself but not with its clearance: the refusal also says which
// clearance passes, and what lowering it costs; that clearance plans.
TEST(BoardOptionRanges, TheNarrowGapRefusalNamesTheClearanceThatPasses) {
  const std::string dir = write_gap_board("gapclearance", 100);
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out --tool-width 0.098 ";
  const ToolRun r = run(board + "--clearance 0.004");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find(" Or keep the tool and lower the clearance: --clearance 0.001 passes "
                       "every gap (the clearance is the room kept between the tool's edge and "
                       "the copper for the curve fit and the machine's contour error; with less, "
                       "the checks may find the tool in the copper).\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(run(board + "--clearance 0.001").code, 0);
  // A tool wider than the gap: no clearance passes, none is offered.
  const ToolRun wide = run("board " + dir + " --no-plot -o " + dir + "/out --tool-width 0.2");
  EXPECT_EQ(wide.code, 1) << wide.err;
  EXPECT_NE(wide.err.find("Use a narrower tool"), std::string::npos) << wide.err;
  EXPECT_EQ(wide.err.find("lower the clearance"), std::string::npos) << wide.err;
}

// Two pads whose flat sides are exactly the tool plus twice its clearance apart: their
// clearances touch and become one contour round both, so the tool cannot separate them. That
// was no narrow gap ("0 narrow gaps", then the check failed with a pair not separated, and
// the refusal's advice for a wider gap named that very tool); it is refused as one, with no
// room to spare, and the tool it advises passes.
TEST(BoardOptionRanges, AGapExactlyAsWideAsTheToolAndItsClearanceIsNarrow) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-opt-flat";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/flat-F.Cu.gbr")  // 2 mm squares, their sides 0.200 mm apart
      << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n%ADD10R,2.000000X2.000000*%\n"
         "D10*\nX10000000Y10000000D03*\nX12200000Y10000000D03*\nM02*\n";
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out --tool-width ";
  const ToolRun r = run(board + "0.184");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("1 place where the copper is no farther apart than the tool width "
                       "0.184 mm plus twice its clearance, so the tool cannot pass between the "
                       "islands with that room:"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("gap 0.200 mm = 0.200 mm (tool 0.184 mm + 2 x 0.008 mm clearance), no "
                       "room to spare, between islands 0 and 1 at (11.100, 10.000) mm"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--tool-width 0.183 passes every gap"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--clearance 0.007 passes every gap"), std::string::npos) << r.err;
  const ToolRun advised = run(board + "0.183");
  EXPECT_EQ(advised.code, 0) << advised.err;
  EXPECT_NE(advised.out.find("check: passed"), std::string::npos) << advised.out;
  EXPECT_EQ(run(board + "0.184 --clearance 0.007").code, 0);
  // Planned anyway, the pair the tool cannot separate is the gap allowed.
  const ToolRun allowed = run(board + "0.184 --allow-narrow-gaps");
  EXPECT_EQ(allowed.code, 0) << allowed.err;
  EXPECT_NE(allowed.out.find("1 narrow gap"), std::string::npos) << allowed.out;
  // `run`'s report lists the gaps it was allowed as `board`'s does (it printed them only).
  const ToolRun ran =
      run("run " + dir + " -o " + dir + "/run --tool-width 0.184 --allow-narrow-gaps");
  ASSERT_EQ(ran.code, 0) << ran.err;
  const std::string name = std::filesystem::path(dir).filename().string();
  const auto report = [](const std::string& path) {
    return nlohmann::json::parse(std::ifstream(path));
  };
  const nlohmann::json gaps = report(dir + "/run/" + name + ".json")["narrow_gaps"];
  ASSERT_EQ(gaps.size(), 1u) << gaps.dump();
  EXPECT_EQ(gaps, report(dir + "/out/" + name + ".board.json")["narrow_gaps"]);
  EXPECT_EQ(gaps[0]["islands"], nlohmann::json::array({0, 1}));
  EXPECT_NEAR(gaps[0]["x_mm"].get<double>(), 11.1, 1e-6);
}

// --surface was read after the job was planned (a user waited for the plan to hear of a
// typo) and in words of its own: it is read with the command line, as every option is.
TEST(BoardOptionRanges, TheSurfaceIsCheckedBeforePlanningInTheOptionsWords) {
  const std::string dir = write_board("surface");
  const std::string run_board = "run " + dir + " -o " + dir + "/out --surface ";
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {run_board + "tilt=0x1mm", "--surface: tilt=0x1mm: '0x1' is not a decimal number\n"},
      {run_board + "bow=infmm", "--surface: bow=infmm: 'inf' is not a finite number\n"},
      {run_board + "tilt=1e999um", "--surface: tilt=1e999um: '1e999' is not a finite number\n"},
      {run_board + "tilt=2mm",
       "--surface: tilt=2mm: 2mm is outside the allowed range -1 .. 1 mm\n"},
      {run_board + "tilt=0.1", "--surface: tilt=0.1: give the length with its unit"},
      {run_board + "tilt=1mm,tilt=2mm", "--surface: 'tilt' is given twice"},
      {"sim --surface noise=1e3mm",
       "--surface: noise=1e3mm: 1e3mm is outside the allowed range 0 .. 0.1 mm\n"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    // The refusal is the first thing said: nothing was read or planned before it.
    EXPECT_EQ(r.err.rfind("engraver: " + c.says, 0), 0u) << c.args << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
}

}  // namespace

namespace {

// "1 holes", "1 sizes", "1 tool changes": a count of one in the singular, in the board's
// report and in the line `run` prints before it simulates.
TEST(BoardReportText, ACountOfOneIsSaidInTheSingular) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-opt-one";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/one-F.Cu.gbr")
      << "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Copper,L1,Top*%\n%ADD10C,1.600000*%\n"
         "D10*\nX10000000Y10000000D03*\nM02*\n";
  std::ofstream(dir + "/one-PTH.drl")
      << "M48\nMETRIC\nT1C0.800\n%\nG90\nG05\nT1\nX10.0Y10.0\nM30\n";
  const ToolRun r = run("board " + dir + " --no-plot -o " + dir + "/out");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("  isolation: 1 island, 1 contour, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  drilling: 1 hole (1 of the board's 1 hole in this side's copper "
                       "pads), 0 slots, 1 size; "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  no cut-out: no outline layer; 1 tool change\n"), std::string::npos)
      << r.out;
  const ToolRun sim = run("run " + dir + " -o " + dir + "/run");
  ASSERT_EQ(sim.code, 0) << sim.err;
  EXPECT_NE(sim.err.find("1 contour, 1 hole, 1 tool change"), std::string::npos) << sim.err;
  std::filesystem::remove_all(dir);
}

// A bottom side after a top side with alignment holes said "0 holes (2 on copper)": the
// holes are drilled with the top side; the count in copper is the layers' alignment check.
TEST(BoardReportText, DrillingSaysWhichSideDrillsAndWhatSitsInThePads) {
  const std::string dir = write_board("report");
  const std::string board = "board " + dir + " --no-plot -o " + dir + "/out ";
  const ToolRun bottom = run(board + "--side bottom --align-holes auto");
  ASSERT_EQ(bottom.code, 0) << bottom.err;
  EXPECT_EQ(bottom.out.find("0 holes ("), std::string::npos) << bottom.out;
  EXPECT_NE(bottom.out.find("  drilling: none on this side: the top side's job drills the holes "
                            "(2 alignment holes; 2 of the board's 2 holes in this side's copper "
                            "pads)\n"),
            std::string::npos)
      << bottom.out;
  const ToolRun top = run(board + "--align-holes auto");
  ASSERT_EQ(top.code, 0) << top.err;
  EXPECT_NE(top.out.find("  drilling: 4 holes (2 of the board's 2 holes in this side's copper "
                         "pads; 2 alignment holes), 0 slots, 2 sizes;"),
            std::string::npos)
      << top.out;
  const ToolRun json = run(board + "--side bottom --align-holes auto --json");
  ASSERT_EQ(json.code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["holes"], 0);
  ASSERT_TRUE(j.contains("board_holes")) << json.out;
  EXPECT_EQ(j["board_holes"], 2);
  EXPECT_EQ(j["holes_on_copper"], 2);
}

}  // namespace

namespace {

// The user guide's range tables ("| option | range | option | range |") give every option of
// the table with the range --help shows, and nothing else.
TEST(BoardOptionRanges, TheGuidesTablesGiveEveryRangeAsTheToolChecksIt) {
  std::ifstream guide(std::string(ENGRAVER_SOURCE_DIR) + "/docs/user-guide.md");
  ASSERT_TRUE(guide) << "docs/user-guide.md";
  std::map<std::string, std::string> documented;  // "--tol" -> "0.001 .. 1 mm"
  std::string line;
  bool table = false;
  while (std::getline(guide, line)) {
    if (line == "| option | range | option | range |") table = true;
    if (!table) continue;
    if (line.rfind("|", 0) != 0) {
      table = false;
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream row(line.substr(1));
    std::string cell;
    while (std::getline(row, cell, '|')) cells.push_back(cell);
    for (size_t c = 0; c + 1 < cells.size(); c += 2) {
      std::string range = cells[c + 1];
      if (range.find_first_not_of(' ') == std::string::npos) continue;  // an empty cell
      range = range.substr(range.find_first_not_of(' '));
      range = range.substr(0, range.find_last_not_of(' ') + 1);
      for (size_t at = cells[c].find("`--"); at != std::string::npos;
           at = cells[c].find("`--", at + 1))
        documented[cells[c].substr(at + 1, cells[c].find('`', at + 1) - at - 1)] = range;
    }
  }
  for (const OptionRange& r : option_ranges()) {
    const std::string expected = bound(r.min) + " .. " + bound(r.max) +
                                 (*r.unit ? std::string(" ") + r.unit : std::string());
    ASSERT_TRUE(documented.count(r.option)) << r.option << " is in no table of the guide";
    EXPECT_EQ(documented[r.option], expected) << r.option;
    documented.erase(r.option);
  }
  EXPECT_TRUE(documented.empty()) << documented.begin()->first << " is not an option of the table";
}

}  // namespace
