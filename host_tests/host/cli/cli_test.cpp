// The `engraver` tool as a user runs it: help, info, points, exit codes.
#include <gtest/gtest.h>
#include <netinet/in.h>  // sockaddr_in
#include <sys/socket.h>  // socket, bind
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "host_tests/host/cli/tool_run.h"

namespace {

// A loopback port nobody listens on (bound to any free port, then let go), and the shell
// lines that start `engraver sim` there and wait until it listens (up to 10 s): a port from
// the process id, slept on for 0.5 s, could be in use or still closing (a flaky exit 6).
uint16_t free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t n = sizeof a;
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), n);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}
std::string start_sim(int port) {
  const std::string p = std::to_string(port);
  return std::string(ENGRAVER_EXE) + " sim --listen 127.0.0.1:" + p +
         " >/dev/null 2>&1 & S=$!; for i in $(seq 200); do (exec 3<>/dev/tcp/127.0.0.1/" + p +
         ") 2>/dev/null && break; sleep 0.05; done; ";
}

const std::string kSample = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

using host_tests::ToolRun;

ToolRun run(const std::string& args) {
  return host_tests::run_tool(ENGRAVER_EXE, args);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
  std::ofstream(path) << text;
  return path;
}

// The tool's stderr is read back and its file removed (one per test process was left in /tmp).
TEST(Cli, ARunKeepsItsStderrApartAndLeavesNoFileBehind) {
  const ToolRun r = run("");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("a command is needed"), std::string::npos) << r.err;
  const std::string err_file =
      testing::TempDir() + "/engraver_stderr_" + std::to_string(getpid()) + ".txt";
  EXPECT_NE(access(err_file.c_str(), F_OK), 0) << err_file << " was left behind";
}

TEST(Cli, HelpShowsAnExampleAndExitsZero) {
  const ToolRun r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("engraver info samples/engraver-word.dxf"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos);
}

// The help footer lists every exit code the user guide's table documents (the footer comes
// from exit_codes.h, the one list of codes).
TEST(Cli, HelpListsEveryDocumentedExitCode) {
  const ToolRun r = run("--help");
  ASSERT_EQ(r.code, 0);
  const size_t at = r.out.find("Exit codes: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string footer = "; " + r.out.substr(at + 12);
  std::ifstream guide(std::string(ENGRAVER_SOURCE_DIR) + "/docs/user-guide.md");
  std::string line;
  bool table = false;
  int codes = 0;
  while (std::getline(guide, line)) {
    if (line == "## Exit codes") table = true;
    if (!table) continue;
    int code = -1;
    if (std::sscanf(line.c_str(), "| %d |", &code) == 1) {
      ++codes;
      EXPECT_NE(footer.find("; " + std::to_string(code) + " "), std::string::npos)
          << "exit code " << code << " is not in --help: " << footer;
    } else if (codes > 0) {
      break;  // the end of the table
    }
  }
  EXPECT_GE(codes, 10);
}

TEST(Cli, VersionExitsZero) {
  const ToolRun r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("engraver "), std::string::npos);
}

TEST(Cli, NoSubcommandIsAUsageError) {
  EXPECT_EQ(run("").code, 2);
}

TEST(Cli, UnknownOptionIsAUsageError) {
  EXPECT_EQ(run("info --bogus " + kSample).code, 2);
}

TEST(Cli, InfoListsEntitiesUnitsAndExtents) {
  const ToolRun r = run("info " + kSample);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("SPLINE 12"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("units:    mm"), std::string::npos);
  EXPECT_NE(r.out.find("124.000 x 30.000 mm"), std::string::npos);
  EXPECT_NE(r.out.find("problems: none"), std::string::npos);
}

// A drawing that takes seconds to read says so as run does (`info big.dxf` was silent until
// its answer): 60 000 lines, about 4 MB, over a second to read in a debug build. A build
// that reads it within the meter's quiet first half second says nothing (a release build
// did, and the test expected the line regardless).
TEST(Cli, InfoAndPointsReportReadingALargeDrawing) {
  std::string dxf = "0\nSECTION\n2\nENTITIES\n";
  for (int i = 0; i < 60000; ++i) {
    const std::string x = std::to_string(i % 200), y = std::to_string(i / 400);
    dxf += "0\nLINE\n8\n0\n10\n" + x + "\n20\n" + y + "\n11\n" + x + ".5\n21\n" + y + ".5\n";
  }
  dxf += "0\nENDSEC\n0\nEOF\n";
  const std::string path = write_temp("read-progress.dxf", dxf);
  for (const char* command : {"info ", "points "}) {
    const auto start = std::chrono::steady_clock::now();
    const ToolRun r = run(command + path + " >/dev/null");
    const double took_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.code, 0) << command << r.err;
    if (took_s > 0.8) {  // the read alone is most of it
      EXPECT_NE(r.err.find("engraver: read: "), std::string::npos) << command << r.err;
      EXPECT_NE(r.err.find(" bytes read (100%)"), std::string::npos) << command << r.err;
    } else if (took_s < 0.5) {
      EXPECT_EQ(r.err.find("engraver: read: "), std::string::npos) << command << r.err;
    }
  }
  std::remove(path.c_str());
}

TEST(Cli, InfoJsonHasEveryCurveWithKnotsAndControlPoints) {
  const ToolRun r = run("info --json " + kSample);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["entities"]["SPLINE"], 12);
  ASSERT_EQ(j["curves"].size(), 17u);
  EXPECT_EQ(j["curves"][0]["degree"], 3);
  EXPECT_EQ(j["curves"][0]["knots"].size(), j["curves"][0]["control_points_mm"].size() + 4);
  EXPECT_FALSE(j["curves"][11]["rational"]);  // the last letter outline
  EXPECT_TRUE(j["curves"][12]["rational"]);   // the first mounting hole (a circle)
  EXPECT_DOUBLE_EQ(j["extents_mm"]["width"].get<double>(), 124.0);
}

// One LINE whose handle (group 5) is `handle`, as bytes from the file.
std::string line_with_handle(const std::string& handle) {
  return "0\nSECTION\n2\nENTITIES\n0\nLINE\n5\n" + handle +
         "\n8\n0\n10\n1\n20\n1\n11\n9\n21\n1\n0\nENDSEC\n0\nEOF\n";
}

// A DXF handle (or any text the file carries) that is not UTF-8 becomes U+FFFD in the JSON;
// the JSON library refused to write it and `info --json` ended as an internal error.
TEST(Cli, InfoJsonOfAFileWithTextThatIsNotUtf8IsValidJson) {
  const std::string path = write_temp("cli_handle.dxf", line_with_handle("2\xc4"));
  const ToolRun r = run("info --json " + path);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["curves"].size(), 1u);
  EXPECT_NE(j["curves"][0]["source"].get<std::string>().find("handle 2\xEF\xBF\xBD,"),
            std::string::npos)
      << j["curves"][0]["source"];
}

// A control byte in a DXF line (here an escape sequence in a handle) is refused as a NUL byte
// is, naming the line and the byte as hex; the terminal never gets the byte itself. (It was
// taken and shown as \x1B.)
TEST(Cli, InfoRefusesAControlByteInADxfLineAndShowsItAsHex) {
  const std::string path = write_temp("cli_escape.dxf", line_with_handle("2\x1b[2J"));
  const ToolRun r = run("info " + path);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(": a control byte (0x1B) in the value of group 5 (binary data in a text "
                       "file?)"),
            std::string::npos)
      << r.err;
}

TEST(Cli, PointsCsvHasHeaderAndRowsPerCurveFromZero) {
  const ToolRun r = run("points --csv " + kSample);
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "curve,x_mm,y_mm");
  std::getline(in, line);
  EXPECT_EQ(line, "0,14.774,12.407");  // the seam of the first e: its first control point
  int last_curve = 0, rows = 1;
  while (std::getline(in, line)) {
    last_curve = std::stoi(line.substr(0, line.find(',')));
    ++rows;
  }
  EXPECT_EQ(last_curve, 16);
  EXPECT_GT(rows, 100);
}

TEST(Cli, CoarserToleranceGivesFewerPoints) {
  const ToolRun fine = run("points --csv --tol 0.005 " + kSample);
  const ToolRun coarse = run("points --csv --tol 0.1 " + kSample);
  ASSERT_EQ(fine.code, 0);
  ASSERT_EQ(coarse.code, 0);
  EXPECT_LT(coarse.out.size(), fine.out.size());
}

TEST(Cli, ToleranceOutOfRangeIsAUsageError) {
  const ToolRun r = run("points --tol 0 " + kSample);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--tol"), std::string::npos);
}

TEST(Cli, MalformedDrawingIsAnInputErrorNamingFileAndEntity) {
  const std::string path =
      write_temp("cli_bad.dxf",
                 "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\n2A\n71\n3\n72\n8\n73\n4\n"
                 "40\n0\n40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n40\n1\n"
                 "10\n0\n20\n0\n10\n1\n20\n1\n10\n2\n20\n1\n10\n3\n20\n0\n0\nENDSEC\n0\nEOF\n");
  const ToolRun r = run("info " + path);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("cli_bad.dxf: SPLINE #1 (handle 2A"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("announces 8 knots (group 72) but lists 7"), std::string::npos) << r.err;
}

TEST(Cli, MissingFileIsAnInputError) {
  const ToolRun r = run("points /nonexistent/x.dxf");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("/nonexistent/x.dxf"), std::string::npos);
}

}  // namespace

namespace {

TEST(Cli, UnknownCommandIsNamedWithTheCommandsThereAre) {
  const ToolRun r = run("bogus");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'bogus' is not an engraver command"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("info, points"), std::string::npos) << r.err;
}

TEST(Cli, EachCommandsHelpHasItsExamplesAndExitCodes) {
  for (const char* cmd : {"info", "points"}) {
    const ToolRun r = run(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.out.find(std::string("engraver ") + cmd + " "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Exit codes: 0"), std::string::npos) << r.out;
  }
  const ToolRun top = run("--help");
  EXPECT_NE(top.out.find("6 send/run/probe: link lost"), std::string::npos) << top.out;
  // The commands with exit codes of their own say them, not the tool's list (the spi
  // commands showed the top-level footer, serve none).
  for (const std::string cmd : {"spi decode", "spi expect", "spi diff", "serve"}) {
    const ToolRun r = run(cmd + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("Example: engraver " + cmd + " "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Exit: 0 "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("4 send/run: machine alarm"), std::string::npos) << r.out;
  }
}

// `info` takes a board folder (host_tests/host/pcb/board_cli_test.cpp); a folder without PCB
// files is refused, saying so.
TEST(Cli, DirectoryGivenAsAFileSaysSo) {
  const std::string dir = testing::TempDir() + "/cli-no-board-" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/notes.txt") << "not a board\n";
  const ToolRun r = run("info " + dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "engraver: " + dir +
                       ": no Gerber or Excellon files there (by their names or first lines)\n  " +
                       dir +
                       "/notes.txt: neither Gerber nor Excellon (by its name or content): "
                       "left out\n");
  // run and points in the same words (they said "is a directory, not a drawing file").
  for (const std::string command : {"run ", "points "}) {
    const ToolRun other = run(command + dir);
    EXPECT_EQ(other.code, 2) << command;
    EXPECT_EQ(other.err, r.err) << command;
  }
  std::filesystem::remove_all(dir);
}

// Board folders are not searched recursively: a folder whose PCB files are in subfolders says
// so.
TEST(Cli, AFolderWhoseFilesAreInSubfoldersSaysTheyAreNotSearched) {
  const std::string dir = testing::TempDir() + "/cli-sub-board-" + std::to_string(getpid());
  std::filesystem::create_directories(dir + "/gerbers");
  std::ofstream(dir + "/gerbers/t-F.Cu.gbr") << "%FSLAX46Y46*%\n%MOMM*%\nM02*\n";
  const ToolRun r = run("info " + dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "engraver: " + dir +
                       ": no Gerber or Excellon files there (by their names or first lines) "
                       "(subfolders are not searched)\n");
  std::filesystem::remove_all(dir);
  EXPECT_NE(run("info --help").out.find("not its subfolders"), std::string::npos);
  EXPECT_NE(run("board --help").out.find("its subfolders are not searched"), std::string::npos);
}

TEST(Cli, MissingFileSaysThereIsNoSuchFile) {
  const ToolRun r = run("info /nonexistent/x.dxf");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("/nonexistent/x.dxf: cannot open the file: no such file"), std::string::npos)
      << r.err;
}

TEST(Cli, UnreadableFileSaysPermissionDenied) {
  if (geteuid() == 0) GTEST_SKIP() << "root reads every file";
  const std::string path = write_temp("cli_noperm.dxf", "0\nEOF\n");
  chmod(path.c_str(), 0);
  const ToolRun r = run("info " + path);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("Permission denied"), std::string::npos) << r.err;
}

const char* kInchProgram =
    "G20 (inch)\nG90\nG0 Z0.5\nT1 M6\n(MSG, Change tool bit)\nM0\nM3\nG4 P1\nG0 X0 Y0\n"
    "G1 Z-0.01 F10\nG1 X1\nG0 Z0.1\nG81 R0.1 Z-0.06 X0.5 Y0.5\nG80\nM5\nM2\n";

TEST(Cli, InfoShowsTheFilesUnitAndItsProgramInOrder) {
  const ToolRun r = run("info " + write_temp("cli_inch.ngc", kInchProgram));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("units:    inch (1 unit = 25.400 mm)"), std::string::npos) << r.out;
  const size_t pause = r.out.find("line 4: pause for the operator: \"Change tool bit\"");
  const size_t cut = r.out.find("line 11: cut path #1");
  const size_t drill = r.out.find("line 13: drill at (12.700, 12.700) mm");
  EXPECT_NE(pause, std::string::npos) << r.out;
  EXPECT_NE(cut, std::string::npos) << r.out;
  EXPECT_NE(drill, std::string::npos) << r.out;
  EXPECT_LT(pause, cut);
  EXPECT_LT(cut, drill);
  const ToolRun j = run("info --json " + write_temp("cli_inch.ngc", kInchProgram));
  ASSERT_EQ(j.code, 0);
  const nlohmann::json doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["units"], "inch");
  EXPECT_EQ(doc["program"].size(), 6u);  // pause, on, dwell, cut, hole, off
}

TEST(Cli, RunRefusesAWorkAreaBeyondTheTravel) {
  const ToolRun r = run("run " + kSample + " --work 600 400 -o " + testing::TempDir());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--work 600 400 mm is beyond the controller's travel of 297 x 210 mm"),
            std::string::npos)
      << r.err;
}

// An Excellon file named .tap (a G-code extension) starting with '%' then M48, as EAGLE and
// Fritzing write drill files: read as drilling by its content, not as G-code.
TEST(Cli, AnExcellonFileNamedTapIsReadByItsContent) {
  const std::string path = write_temp(
      "cli_drill.tap", "%\nM48\nINCH\nT1C0.0315\n%\nG90\nG05\nT1\nX0.3937Y0.3937\nM30\n");
  const ToolRun r = run("info " + path);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("format:    Excellon"), std::string::npos) << r.out;
}

TEST(Cli, RunOnATooLargeDrawingSaysWhatWouldFit) {
  const ToolRun r = run("run " + kSample + " --scale 3 -o " + testing::TempDir());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("the drawing is 372 x 90 mm at --scale 3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("It fits at --scale 2.395 or smaller"), std::string::npos) << r.err;
}

}  // namespace

namespace {

// A program the way pcb2gcode writes one, milling then drilling: dwells, a tool change
// with its message, spindle, G81 holes; through the simulated machine to the end.
const char* kPcbJob =
    "( pcb2gcode style )\nG94\nG20\nG90\nG00 S10000\nG64 P0.0004\nG01 F20\n"
    "G00 Z1.0 (Retract to tool change height)\nT1\nM5\nG04 P1.0\n"
    "(MSG, Change tool bit to mill diameter 0.00800in)\nM6\nM0\nM3\nG04 P1.0\nG04 P0\n"
    "G00 Z0.08\nG00 X0.1 Y0.1\nG01 Z-0.004 F10\nG04 P0\nG01 F20\nG01 X0.5 Y0.1\n"
    "G01 X0.5 Y0.3\nG01 X0.1 Y0.3\nG01 X0.1 Y0.1\nG00 Z1.0\n"
    "T2\nM5\nG04 P1.0\n(MSG, Change tool bit to drill size 0.0315inch)\nM6\nM0\nM3\nG0 Z0.08\n"
    "G04 P1.0\nG81 R0.08 Z-0.07 F10 X0.2 Y0.2\nX0.4 Y0.2\nG80\nG00 Z1.0\nM5\nG04 P1.0\nM9\nM2\n";

TEST(Cli, RunCarriesAPcbProgramWithToolChangesDwellsAndHolesToTheEnd) {
  const std::string out = testing::TempDir() + "/cli_pcbjob_" + std::to_string(getpid());
  const ToolRun r = run("run " + write_temp("cli_pcbjob.ngc", kPcbJob) + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  std::ifstream in(out + "/" + std::to_string(getpid()) + "-cli_pcbjob.json");
  ASSERT_TRUE(in) << "no report";
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["outcome"], "completed");
  EXPECT_EQ(j["pauses_confirmed_by_simulated_operator"], 2);  // one stop per tool change
  EXPECT_EQ(j["spindle_on_at_end"], false);
  // The 0.4 x 0.2 in rectangle was cut, and nothing else: the travel at the R plane
  // (0.08 in) to and between the holes is not cutting (it once counted, 40 mm in all).
  EXPECT_NEAR(j["traced_cut_mm"].get<double>(), 1.2 * 25.4, 0.1);
  // A short job's plot path keeps its step: a fraction of the samples, within the budget.
  const nlohmann::json& kept = j["plot_tool_path"];
  EXPECT_GT(kept["samples_kept"].get<size_t>(), 10u);
  EXPECT_LT(kept["samples_kept"].get<size_t>(), kept["samples_simulated"].get<size_t>());
  EXPECT_GT(kept["step_mm"].get<double>(), 0.0);
  EXPECT_EQ(r.out.find("thinned to"), std::string::npos) << r.out;
  // Status polled as `send` polls a real link (every 250 ms, here of machine time): the
  // frames and bytes reported are what a real run puts on the wire (it polled every 50 ms,
  // five times the job's own bytes).
  const double polls_at_250ms = j["simulated_machine_ms"].get<double>() / 250;
  EXPECT_GT(polls_at_250ms, 100);
  EXPECT_NEAR(j["status_queries"].get<double>(), polls_at_250ms, 0.05 * polls_at_250ms);
}

}  // namespace

namespace {

// The report of `run` on a file, for the plan option tests.
nlohmann::json run_report(const std::string& file, const std::string& options) {
  const std::string out = testing::TempDir() + "/cli_opts_" + std::to_string(getpid());
  const ToolRun r = run("run " + file + " " + options + " -o " + out);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  const std::string stem = file.substr(file.rfind('/') + 1, file.rfind('.') - file.rfind('/') - 1);
  std::ifstream in(out + "/" + stem + ".json");
  if (!in) return nlohmann::json::object();
  return nlohmann::json::parse(in);
}

const char* kCircle =
    "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"
    "0\nCIRCLE\n8\n0\n10\n50\n20\n50\n40\n5\n0\nENDSEC\n0\nEOF\n";

TEST(Cli, OffsetKeepsTheFilesZeroAndSaysWhatFits) {
  const std::string file = write_temp("cli_offset.ngc", "G21\nG0 X0 Y0\nG1 X10 Y0 F100\n");
  // Rapids: from the machine zero to the start, and back from the end (10, 0) + offset.
  EXPECT_NEAR(run_report(file, "")["planned_rapid_mm"].get<double>(), 10.0, 1e-3);
  EXPECT_NEAR(run_report(file, "--offset 20 30")["planned_rapid_mm"].get<double>(),
              std::hypot(20.0, 30.0) + std::hypot(30.0, 30.0), 1e-3);
  const ToolRun far = run("run " + file + " --offset 290 0 -o " + testing::TempDir());
  EXPECT_EQ(far.code, 1);
  EXPECT_NE(far.err.find("It fits with --offset at most 287 0 mm."), std::string::npos) << far.err;
  const ToolRun below = run("run " + file + " --offset -3 0 -o " + testing::TempDir());
  EXPECT_NE(below.err.find("add at least 3 0 mm to --offset"), std::string::npos) << below.err;
  EXPECT_EQ(run("run " + file + " --offset 1 1 --margin 2").code, 2);
}

TEST(Cli, ToolSideOffsetsTheCutOnTheController) {
  const std::string file = write_temp("cli_side.dxf", kCircle);
  const double pi = 3.14159265358979;
  // A counter-clockwise circle of radius 5: left of travel is inside.
  EXPECT_NEAR(run_report(file, "--margin 1")["traced_cut_mm"].get<double>(), 2 * pi * 5, 0.05);
  EXPECT_NEAR(run_report(file, "--margin 1 --tool-side left --tool-radius 0.5")["traced_cut_mm"]
                  .get<double>(),
              2 * pi * 4.5, 0.05);
  EXPECT_NEAR(run_report(file, "--margin 1 --tool-side right --tool-radius 0.5")["traced_cut_mm"]
                  .get<double>(),
              2 * pi * 5.5, 0.05);
  const ToolRun r = run("run " + file + " --tool-side left -o " + testing::TempDir());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--tool-side left needs --tool-radius MM above 0"), std::string::npos);
}

TEST(Cli, FitToleranceAndDrillModeChangeWhatIsSent) {
  std::string program = "G21\nG0 X20 Y10\nG1 Z-0.1 F100\n";
  for (int i = 1; i <= 120; ++i) {
    const double a = 2 * 3.14159265358979 * i / 120;
    program += "G1 X" + std::to_string(10 + 10 * std::cos(a)) + " Y" +
               std::to_string(10 + 10 * std::sin(a)) + "\n";
  }
  program += "G0 Z1\nG81 R1 Z-1 F60 X5 Y5\nX8 Y5\nG80\nM2\n";
  const std::string file = write_temp("cli_fit.ngc", program);
  const nlohmann::json fitted = run_report(file, "");
  const nlohmann::json moves = run_report(file, "--fit-tol 0");
  const nlohmann::json z_moves = run_report(file, "--drill-as-z-moves");
  // 120 G1 moves: a few fitted splines by default, one command each with --fit-tol 0.
  EXPECT_GE(moves["commands"].get<int>(), 120);
  EXPECT_LT(fitted["commands"].get<int>(), 30);
  EXPECT_NEAR(moves["traced_cut_mm"].get<double>(), fitted["traced_cut_mm"].get<double>(), 0.05);
  // Each of the two holes: one drill command, or Z moves (down, up) in its place.
  EXPECT_GT(z_moves["commands"].get<int>(), fitted["commands"].get<int>());
  EXPECT_EQ(z_moves["outcome"], "completed");
}

// send --resume-at takes INDEX or INDEX:POINT; anything else is a usage error before any
// connection is tried.
TEST(Cli, SendResumeAtRejectsABadPositionAsAUsageError) {
  const auto r = run("send " + kSample + " --to tcp://127.0.0.1:9 --resume-at 12:x");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--resume-at: '12:x'"), std::string::npos) << r.err;
}

// send --resume on a controller that never ran a job (as after a restart): refused with what to
// do instead, nothing sent.
TEST(Cli, SendResumeOnAControllerWithoutJobProgressSaysWhatToDo) {
  const int port = free_port();
  const std::string exe = ENGRAVER_EXE;
  const std::string script = "'" + start_sim(port) + exe + " send " + kSample +
                             " --to tcp://127.0.0.1:" + std::to_string(port) +
                             " --resume; r=$?; kill $S; exit $r'";
  const auto r = host_tests::run_tool("bash -c", script);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("no job progress"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--resume-at"), std::string::npos) << r.err;
}

// send (and probe) --no-zero to a fresh simulator (not zeroed): refused before anything is
// sent, exit 1 (send streamed the set-up and ended with exit 5 at the first move).
TEST(Cli, SendAndProbeNoZeroRefuseAMachineThatIsNotZeroed) {
  const std::string exe = ENGRAVER_EXE;
  const std::string map = testing::TempDir() + "/no_zero_" + std::to_string(getpid()) + ".json";
  for (const std::string command : {"send", "probe"}) {
    const int port = free_port();  // each its own: the last one may still be closing
    const std::string script = "'" + start_sim(port) + exe + " " + command + " " + kSample +
                               " --to tcp://127.0.0.1:" + std::to_string(port) + " --no-zero" +
                               (command == "probe" ? " --height-map " + map : "") +
                               "; r=$?; kill $S; wait $S; exit $r'";
    const auto r = host_tests::run_tool("bash -c", script);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("engraver: the machine is not zeroed and --no-zero does not start manual "
                         "zeroing: nothing was sent (without --no-zero, " +
                         command +
                         " starts it: jog to the corner with the joystick and press confirm)\n"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find(" -> tcp://"), std::string::npos) << r.err;  // no streaming began
  }
  std::remove(map.c_str());
}

}  // namespace
