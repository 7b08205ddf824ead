// The `engraver` tool as a user runs it: help, info, points, exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace {

const std::string kSample = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

struct ToolRun {
  int code;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs the tool with args (shell words), capturing stdout and stderr separately.
ToolRun run(const std::string& args) {
  const std::string err_path =
      testing::TempDir() + "/cli_stderr_" + std::to_string(getpid()) + ".txt";
  const std::string cmd = std::string(ENGRAVER_EXE) + " " + args + " 2>" + err_path;
  ToolRun r;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_path);
  std::stringstream s;
  s << e.rdbuf();
  r.err = s.str();
  return r;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, HelpShowsAnExampleAndExitsZero) {
  const ToolRun r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("engraver info samples/engraver-word.dxf"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos);
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
