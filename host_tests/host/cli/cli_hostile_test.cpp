// Hostile drawings through the tool as a user runs it: a clean, specific message on stderr
// and exit code 2 (input error), never a crash or a bare exception type (issue 13).
#include <dirent.h>  // opendir
#include <gtest/gtest.h>
#include <sys/stat.h>  // mkfifo
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
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

// A FIFO or a device where a file is expected is refused before it is opened (opening a FIFO
// waits for a writer: `info f.dxf` hung), by every reader: exit 2, "not a regular file".
TEST(CliHostile, AFifoOrDeviceIsRefusedWithoutWaitingForAWriter) {
  const std::string dir = testing::TempDir() + "/" + std::to_string(getpid()) + "-fifo";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string word = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";
  const std::string timed = std::string("timeout 10 ") + ENGRAVER_EXE;
  for (const char* name : {"f.dxf", "f.gbr", "f.drl", "f.nc", "f.map.json", "f.vcd"}) {
    const std::string f = dir + "/" + name;
    ASSERT_EQ(mkfifo(f.c_str(), 0644), 0) << f;
  }
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"info " + dir + "/f.dxf", dir + "/f.dxf"},
      {"info " + dir + "/f.gbr", dir + "/f.gbr"},
      {"info " + dir + "/f.drl", dir + "/f.drl"},
      {"info " + dir + "/f.nc", dir + "/f.nc"},
      {"info /dev/null", "/dev/null"},
      {"run " + dir + "/f.dxf -o " + dir + "/out", dir + "/f.dxf"},
      {"points " + dir + "/f.dxf", dir + "/f.dxf"},
      {"board --top " + dir + "/f.gbr -o " + dir + "/out", dir + "/f.gbr"},
      {"board --drill " + dir + "/f.drl -o " + dir + "/out", dir + "/f.drl"},
      {"run " + word + " --height-map " + dir + "/f.map.json -o " + dir + "/out",
       dir + "/f.map.json"},
      {"spi diff " + dir + "/f.vcd " + dir + "/f.dxf", dir + "/f.dxf"},
      {"spi decode " + dir + "/f.vcd", dir + "/f.vcd"},
  };
  for (const auto& [args, file] : cases) {
    const ToolRun r = host_tests::run_tool(timed, args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(file + ": not a regular file (a pipe, device or socket)"),
              std::string::npos)
        << args << "\n"
        << r.err;
  }
  std::filesystem::remove_all(dir);
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
