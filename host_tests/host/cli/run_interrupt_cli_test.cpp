// `engraver run` and Ctrl-C (issue 24): it exited 130 without a word, while probing and while
// the job ran. Now the simulated machine stops as `send` stops a real one (#X), the tool goes
// up, the run says what was done and ends with the documented code (docs/user-guide.md).
#include <fcntl.h>  // O_WRONLY
#include <gtest/gtest.h>
#include <poll.h>      // poll
#include <pty.h>       // forkpty
#include <signal.h>    // kill, SIGINT, SIGTERM
#include <spawn.h>     // posix_spawn
#include <sys/wait.h>  // waitpid
#include <unistd.h>    // getpid

#include <chrono>      // steady_clock
#include <filesystem>  // temp paths
#include <fstream>     // std::ifstream
#include <sstream>     // std::stringstream
#include <string>      // std::string
#include <thread>      // sleep_for
#include <vector>      // std::vector

#include "host_tests/host/cli/tool_run.h"  // read_text

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

using host_tests::read_text;

struct Interrupted {
  int code = -1;  // -1: still running 20 s after the signal (then killed)
  std::string err;
  std::string outdir;  // -o
};

// The folder for this test process's run.
std::string fresh_dir() {
  const std::string dir = testing::TempDir() + "/run_interrupt_" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// `engraver run ARGS --realtime -o DIR/out` as argv.
std::vector<std::string> run_command(const std::vector<std::string>& run_args,
                                     const std::string& dir) {
  std::vector<std::string> args = {ENGRAVER_EXE, "run"};
  args.insert(args.end(), run_args.begin(), run_args.end());
  for (const std::string& a : {std::string("--realtime"), std::string("-o"), dir + "/out"})
    args.push_back(a);
  return args;
}

// The exit code of a process that ended (128 + its signal if one ended it), or -1 when it
// still runs 20 s on (then it is killed).
int exit_within_20s(pid_t pid) {
  const auto end = Clock::now() + std::chrono::seconds(20);
  int status = 0;
  while (Clock::now() < end) {
    if (waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

// Runs `engraver run ARGS` in real time, waits until it has said something on stderr (the
// plan made, the simulation started), lets it run `after_s` more and sends `sig`.
Interrupted interrupt_run(const std::vector<std::string>& run_args, double after_s, int sig) {
  const std::string dir = fresh_dir();
  const std::string err_path = dir + "/stderr.txt";
  std::vector<std::string> args = run_command(run_args, dir);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  Interrupted r;
  r.outdir = dir + "/out";
  if (posix_spawn(&pid, ENGRAVER_EXE, &files, nullptr, argv.data(), environ) != 0) return r;
  posix_spawn_file_actions_destroy(&files);
  const auto started_by = Clock::now() + std::chrono::seconds(60);
  while (read_text(err_path).empty() && Clock::now() < started_by)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::duration<double>(after_s));
  kill(pid, sig);
  r.code = exit_within_20s(pid);
  r.err = read_text(err_path);
  return r;
}

// Appends what the terminal shows to *text; false when nothing more will come.
bool read_terminal(int master, std::string* text) {
  pollfd p{master, POLLIN, 0};
  if (poll(&p, 1, 20) <= 0) return true;
  char buf[4096];
  const ssize_t n = read(master, buf, sizeof buf);
  if (n > 0) text->append(buf, static_cast<size_t>(n));
  return n > 0;  // EIO once the process has gone
}

// The same on a terminal of its own (a pseudo-terminal, stdout and stderr on it), where the
// operator presses Ctrl-C `after_s` after the run began to speak: the terminal sends SIGINT.
Interrupted ctrl_c_run(const std::vector<std::string>& run_args, double after_s) {
  const std::string dir = fresh_dir();
  std::vector<std::string> args = run_command(run_args, dir);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Interrupted r;
  r.outdir = dir + "/out";
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid < 0) return r;
  if (pid == 0) {
    execv(ENGRAVER_EXE, argv.data());
    _exit(127);
  }
  const auto started_by = Clock::now() + std::chrono::seconds(60);
  while (r.err.empty() && Clock::now() < started_by) read_terminal(master, &r.err);
  const auto press_at = Clock::now() + std::chrono::duration<double>(after_s);
  while (Clock::now() < press_at) read_terminal(master, &r.err);
  const char ctrl_c = 0x03;
  EXPECT_EQ(write(master, &ctrl_c, 1), 1);
  const auto end = Clock::now() + std::chrono::seconds(20);
  while (Clock::now() < end && read_terminal(master, &r.err)) {
  }
  r.code = exit_within_20s(pid);
  close(master);
  return r;
}

const std::string kWord = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

// The last line the run wrote to stderr: how it ended, said once.
std::string last_line(const std::string& err) {
  const size_t end = err.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  const size_t start = err.rfind('\n', end);
  return err.substr(start == std::string::npos ? 0 : start + 1,
                    end - (start == std::string::npos ? 0 : start + 1) + 1);
}

// The whole number after `"key": ` in a report (-1: not there).
long report_number(const std::string& report, const std::string& key) {
  const size_t at = report.find("\"" + key + "\": ");
  return at == std::string::npos ? -1 : std::stol(report.substr(at + key.size() + 4));
}

// The report written, marked stopped: the figures so far are not lost, and it says how far
// the job got (the commands executed, as the message counts them), not the whole job.
void expect_stopped_report(const Interrupted& r, const std::string& message_begins) {
  const std::string report = read_text(r.outdir + "/engraver-word.json");
  EXPECT_NE(report.find("\"stopped\": true"), std::string::npos) << report;
  const long executed = report_number(report, "commands_executed");
  const long all = report_number(report, "commands") + report_number(report, "setup_commands");
  EXPECT_GE(executed, 0) << report;
  EXPECT_LT(executed, all) << report;
  EXPECT_NE(report.find(" after " + std::to_string(executed) + " of " + std::to_string(all) +
                        " commands"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("\"outcome\": \"aborted\""), std::string::npos) << report;
  EXPECT_NE(report.find("\"message\": \"" + message_begins), std::string::npos) << report;
  EXPECT_TRUE(std::filesystem::exists(r.outdir + "/engraver-word.svg"));
}

// The word takes about a minute of machine time in real time: stopped a second in. Ctrl-C on
// the run's terminal is the operator's.
TEST(RunInterruptCli, CtrlCWhileTheJobRunsAbortsItRaisesTheToolAndExitsThree) {
  const Interrupted r = ctrl_c_run({kWord}, 1.5);
  EXPECT_EQ(r.code, 3) << r.err;  // was 130 (killed by SIGINT), without a word
  EXPECT_NE(r.err.find("engraver: run stopped: aborted by the operator (Ctrl-C) "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the tool raised to Z 2.000 mm"), std::string::npos) << r.err;
  EXPECT_EQ(last_line(r.err).rfind("engraver: run stopped: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("job aborted:"), std::string::npos) << r.err;
  // The summary (on the same terminal) counts what ran, not "sent 111 commands".
  EXPECT_NE(r.err.find(" commands executed (the set-up included), of a job of 111 commands"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("  sent "), std::string::npos) << r.err;
  expect_stopped_report(r, "aborted by the operator (Ctrl-C) ");
}

// A signal from another process (timeout, kill) is not the operator: it is named (an outside
// tester's `timeout` read "aborted by the operator"), and the report so far is written (it
// wrote none: the figures were lost).
TEST(RunInterruptCli, SigtermWhileTheJobRunsSaysSoAndWritesTheReportSoFar) {
  const Interrupted r = interrupt_run({kWord}, 1.5, SIGTERM);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(last_line(r.err).rfind("engraver: run stopped: stopped by SIGTERM ", 0), 0u) << r.err;
  EXPECT_NE(last_line(r.err).find("the plot and the report (" + r.outdir +
                                  "/engraver-word.json, \"stopped\": true) show the job so far"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("aborted by the operator"), std::string::npos) << r.err;
  expect_stopped_report(r, "stopped by SIGTERM ");
}

TEST(RunInterruptCli, SigintFromAProcessIsNamedToo) {
  const Interrupted r = interrupt_run({kWord}, 1.5, SIGINT);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(last_line(r.err).rfind("engraver: run stopped: stopped by SIGINT ", 0), 0u) << r.err;
}

// While `run --probe` touches the simulated blank: the touch stops, the tool goes up, and the
// run ends as `probe` does (exit 5: the controller reports the touch stopped).
TEST(RunInterruptCli, SigtermWhileProbingStopsTheTouchRaisesTheToolAndExitsAsProbeDoes) {
  const Interrupted r = interrupt_run({kWord, "--surface", "tilt=0.1mm", "--probe"}, 1.5, SIGTERM);
  EXPECT_EQ(r.code, 5) << r.err;  // was 143 (killed by SIGTERM)
  EXPECT_NE(r.err.find("engraver: probing stopped: the tool raised to Z 2.000 mm"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("stopped by SIGTERM"), std::string::npos) << r.err;
  EXPECT_EQ(last_line(r.err).rfind("engraver: probing stopped: ", 0), 0u) << r.err;
}

}  // namespace
