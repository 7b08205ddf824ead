// `engraver send` and Ctrl-C (SIGINT) or SIGTERM while the job cuts (issue 24): it said "job
// aborted" twice and left the tool at depth. Now the machine stops (#X), the tool goes up to
// the travel height as in `run` and `probe`, the ending is said once, and `--resume` still
// finishes the job.
#include <fcntl.h>  // O_WRONLY
#include <gtest/gtest.h>
#include <signal.h>    // kill, SIGINT, SIGTERM
#include <spawn.h>     // posix_spawn
#include <sys/wait.h>  // waitpid
#include <unistd.h>    // getpid

#include <atomic>      // std::atomic
#include <chrono>      // steady_clock
#include <filesystem>  // temp paths
#include <fstream>     // std::ifstream
#include <sstream>     // std::stringstream
#include <string>      // std::string
#include <thread>      // sleep_for
#include <vector>      // std::vector

#include "host/lib/plan/job_plan.h"  // defaults::kZUpMm
#include "host/lib/sim/sim_server.h"

#include "host_tests/host/cli/tool_run.h"  // read_text

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

using host_tests::read_text;

size_t count_of(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// Runs engraver with `args` ("TO" becomes the simulated machine), stderr to `err_path`;
// with `sig`, sends it once the tool cuts (below the copper) and waits for the exit.
int run_engraver(std::vector<std::string> args, int port, const std::string& err_path,
                 host::sim::SimMachine& machine, int sig) {
  for (std::string& a : args)
    if (a == "TO") a = "tcp://127.0.0.1:" + std::to_string(port);
  args.insert(args.begin(), ENGRAVER_EXE);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, ENGRAVER_EXE, &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return -3;
  if (sig != 0) {
    const auto by = Clock::now() + std::chrono::seconds(60);
    while (machine.position().z_mm > -0.02 && Clock::now() < by)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    EXPECT_LT(machine.position().z_mm, -0.02) << "the job never cut";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // on its path, at depth
    kill(pid, sig);
  }
  const auto end = Clock::now() + std::chrono::seconds(20);
  int status = 0;
  while (Clock::now() < end) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;  // still running
}

// One 60 mm line: 6 s at 10 mm/s in real time, time to interrupt it mid-cut.
std::string write_line_dxf() {
  const std::string path =
      testing::TempDir() + "/send_interrupt_" + std::to_string(getpid()) + ".dxf";
  std::ofstream(path) << "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n1\n20\n1\n11\n61\n21\n1"
                         "\n0\nENDSEC\n0\nEOF\n";
  return path;
}

// `says`: how the ending names who stopped the job (a signal from a process is not the
// operator: it said "aborted by the operator" for a kill too).
void check_interrupted_send(int sig, const std::string& says) {
  host::sim::SimOptions o;
  host::sim::SimMachine machine(o);
  host::sim::ServerOptions so;
  so.port = 0;
  so.realtime = true;
  host::sim::SimServer server(machine, so);
  std::atomic<bool> stop{false};
  std::thread serving([&] { server.run(stop); });
  const std::string err =
      testing::TempDir() + "/send_interrupt_" + std::to_string(getpid()) + ".txt";

  const std::string line = write_line_dxf();
  const int code =
      run_engraver({"send", line, "--to", "TO", "--feed", "10"}, server.port(), err, machine, sig);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const double z_mm = machine.position().z_mm;
  const std::string said = read_text(err);
  EXPECT_EQ(code, 3) << said;
  EXPECT_EQ(count_of(said, "job aborted"), 1u) << said;  // was twice
  EXPECT_NE(said.find("engraver: job aborted: " + says + " after "), std::string::npos) << said;
  EXPECT_NE(said.find("; the tool raised to Z 2.000 mm\n"), std::string::npos) << said;
  EXPECT_NEAR(z_mm, host::defaults::kZUpMm, 0.01) << "the tool up, not left at depth";

  // The lift keeps the job's progress: --resume finishes it.
  const int resumed = run_engraver({"send", line, "--to", "TO", "--feed", "10", "--resume"},
                                   server.port(), err, machine, 0);
  const std::string resume_said = read_text(err);
  EXPECT_EQ(resumed, 0) << resume_said;
  EXPECT_NE(resume_said.find("engraver: resuming at "), std::string::npos) << resume_said;
  EXPECT_EQ(count_of(resume_said, "job completed"), 1u) << resume_said;
  stop = true;
  serving.join();
  std::filesystem::remove(err);
  std::filesystem::remove(line);
}

TEST(SendInterruptCli, SigintWhileCuttingRaisesTheToolAndSaysTheEndingOnce) {
  check_interrupted_send(SIGINT, "stopped by SIGINT");
}

TEST(SendInterruptCli, SigtermWhileCuttingRaisesTheToolAndSaysTheEndingOnce) {
  check_interrupted_send(SIGTERM, "stopped by SIGTERM");
}

}  // namespace
