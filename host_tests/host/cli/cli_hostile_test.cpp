// Hostile drawings through the tool as a user runs it: a clean, specific message on stderr
// and exit code 2 (input error), never a crash or a bare exception type (issue 13).
#include <dirent.h>  // opendir
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::ToolRun;

ToolRun run_info(const std::string& file) {
  return host_tests::run_tool(ENGRAVER_EXE, "info '" + file + "'");
}

std::string write_temp(const std::string& name, const std::string& bytes) {
  const std::string path = testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(CliHostile, SplineAfterEofIsAnInputError) {
  const std::string f = write_temp("after-eof.dxf", "0\nEOF\n0\nSPLINE\n73\n8\n73\n715827883\n");
  const ToolRun r = run_info(f);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "engraver: " + f +
                       ": line 3: data after the end-of-file marker '0 EOF' of line 1 (a "
                       "damaged or concatenated file?)\n");
}

TEST(CliHostile, SplineDegreeOverflowIsAnInputError) {
  const std::string f = write_temp(
      "degree.dxf", "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n5981035710\n0\nENDSEC\n0\nEOF\n");
  const ToolRun r = run_info(f);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "engraver: " + f +
                       ": line 7, in SPLINE starting at line 5: group 71 value 5981035710 is "
                       "out of range (a 32-bit integer: -2147483648..2147483647)\n");
}

// A copy of an executable named as a drawing or a drill file (an outside tester's /bin/ls):
// "not a DXF/Excellon file: binary data", exit 2, as for Gerber; it was an escaped line
// "is not a DXF group code", and for Excellon a quote cut open at the first NUL.
TEST(CliHostile, BinaryDataIsNotADxfOrExcellonFile) {
  const std::string elf(
      "\x7F"
      "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0>\0\nmore",
      24);
  const std::string dxf = write_temp("ls.dxf", elf);
  const ToolRun info = run_info(dxf);
  EXPECT_EQ(info.code, 2);
  EXPECT_EQ(info.err,
            "engraver: " + dxf + ": line 1: not a DXF file: binary data (a NUL byte at byte 7)\n");
  const std::string drl = write_temp("ls.drl", elf);
  const ToolRun board = host_tests::run_tool(
      ENGRAVER_EXE, "board --drill '" + drl + "' -o '" + testing::TempDir() + "'");
  EXPECT_EQ(board.code, 2);
  EXPECT_EQ(board.err,
            "engraver: " + drl + ":1: not an Excellon file: binary data (a NUL byte at byte 7)\n");
}

// The reproducers in ../shared/samples/hostile (skipped when ../shared is absent).
TEST(CliHostile, SharedReproducersExitTwoWithTheFileNamed) {
  const std::string dir = std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/hostile/";
  DIR* d = opendir(dir.c_str());
  if (d == nullptr) GTEST_SKIP() << dir << " not present";
  std::vector<std::string> files;
  while (dirent* e = readdir(d)) {
    const std::string n = e->d_name;
    if (n.size() > 4 && n.compare(n.size() - 4, 4, ".dxf") == 0) files.push_back(dir + n);
  }
  closedir(d);
  ASSERT_FALSE(files.empty());
  for (const std::string& f : files) {
    const ToolRun r = run_info(f);
    EXPECT_EQ(r.code, 2) << f << ": " << r.err;
    EXPECT_EQ(r.err.rfind("engraver: " + f + ": line ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find("std::"), std::string::npos) << r.err;
  }
}

}  // namespace
