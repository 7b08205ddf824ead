// Runs the `engraver` executable as a user would, for the CLI tests: its exit code, stdout and
// stderr, each kept apart.
#ifndef HOST_TESTS_HOST_CLI_TOOL_RUN_H
#define HOST_TESTS_HOST_CLI_TOOL_RUN_H

#include <gtest/gtest.h>  // testing::TempDir
#include <sys/wait.h>     // WIFEXITED, WEXITSTATUS
#include <unistd.h>       // getpid

#include <cstdio>   // popen, fread, pclose, std::remove
#include <fstream>  // std::ifstream
#include <sstream>  // std::stringstream
#include <string>   // std::string

namespace host_tests {

// The whole file at path ("" when it cannot be read): what a stopped process wrote.
inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct ToolRun {
  int code;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `exe args` (args are shell words). stderr goes through a per-process temp file, so
// test processes that ctest runs in parallel never share one; it is removed once read.
inline ToolRun run_tool(const std::string& exe, const std::string& args) {
  const std::string err_path =
      testing::TempDir() + "/engraver_stderr_" + std::to_string(getpid()) + ".txt";
  const std::string cmd = exe + " " + args + " 2>" + err_path;
  ToolRun r;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_text(err_path);
  std::remove(err_path.c_str());  // one per test process: left, they piled up in /tmp
  return r;
}

}  // namespace host_tests

#endif  // HOST_TESTS_HOST_CLI_TOOL_RUN_H
