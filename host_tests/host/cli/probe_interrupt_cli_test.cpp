// `engraver probe` and `send --probe` and Ctrl-C (SIGTERM): the touch under way stops at
// once (#X), and the tool goes up to the travel height before engraver exits, not left where
// the descent stopped.
#include <gtest/gtest.h>
#include <signal.h>    // kill, SIGINT
#include <spawn.h>     // posix_spawn
#include <sys/wait.h>  // waitpid

#include <chrono>      // steady_clock
#include <filesystem>  // temp paths
#include <functional>  // std::function
#include <string>      // std::string
#include <thread>      // sleep_for
#include <vector>      // std::vector

#include "host/lib/plan/job_plan.h"  // defaults::kZUpMm
#include "host/lib/sim/sim_server.h"
#include "host_tests/host/freezing_proxy.h"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

// A waitpid with a time limit: the exit status, or -1 (still running: then it is killed).
int wait_exit(pid_t pid, double limit_s) {
  const auto end = Clock::now() + std::chrono::duration<double>(limit_s);
  int status = 0;
  while (Clock::now() < end) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

// How an engraver command probing a flat blank ended when `sig` came in the middle of its
// first descent: its exit code, how long it took after the signal, where the tool stands.
struct Interrupted {
  int code = -1;
  double took_s = 0;
  double tool_z_mm = -9;
};

// `args` after the command name: the input, then its options; "TO" becomes the machine,
// reached through a proxy. `interrupt` acts in the middle of the first descent (a signal, a
// frozen link).
Interrupted interrupt_first_descent(
    std::vector<std::string> args,
    const std::function<void(pid_t, host::test::FreezingProxy&)>& interrupt, double limit_s = 10) {
  host::sim::SimOptions o;
  o.surface_um = [](int32_t, int32_t) { return 0; };  // a flat blank at Z 0
  host::sim::SimMachine machine(o);
  host::sim::ServerOptions so;
  so.port = 0;
  so.realtime = true;  // a descent at 1 mm/s takes a second: time to interrupt it
  host::sim::SimServer server(machine, so);
  std::atomic<bool> stop{false};
  std::thread serving([&] { server.run(stop); });
  host::test::FreezingProxy proxy(server.port());
  for (std::string& a : args)
    if (a == "TO") a = proxy.address();
  args.insert(args.begin(), ENGRAVER_EXE);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Interrupted r;
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, ENGRAVER_EXE, nullptr, nullptr, argv.data(), environ), 0);
  // The first descent under way (from Z 1 mm down to the copper at Z 0).
  const auto end = Clock::now() + std::chrono::seconds(30);
  bool descending = false;
  while (!descending && Clock::now() < end) {
    const host::sim::ToolSample t = machine.position();
    descending = t.z_mm < 0.7 && t.z_mm > 0.2;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_TRUE(descending);
  interrupt(pid, proxy);
  const auto interrupted = Clock::now();
  r.code = wait_exit(pid, limit_s);
  r.took_s = std::chrono::duration<double>(Clock::now() - interrupted).count();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  r.tool_z_mm = machine.position().z_mm;
  proxy.freeze(false);
  stop = true;
  serving.join();
  return r;
}

std::function<void(pid_t, host::test::FreezingProxy&)> signal(int sig) {
  return [sig](pid_t pid, host::test::FreezingProxy&) { kill(pid, sig); };
}

std::string temp_map(const std::string& name) {
  const std::string map =
      testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".map.json";
  std::filesystem::remove(map);
  return map;
}

const std::string kWord = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

TEST(ProbeCli, CtrlCStopsTheTouchAtOnceAndRaisesTheTool) {
  const std::string map = temp_map("probe_interrupt");
  const Interrupted r =
      interrupt_first_descent({"probe", kWord, "--to", "TO", "--height-map", map}, signal(SIGINT));
  EXPECT_EQ(r.code, 5) << "-1: still probing 10 s after Ctrl-C";
  EXPECT_LT(r.took_s, 8.0);  // the stop, a new session and the lift, on a loaded PC
  EXPECT_FALSE(std::filesystem::exists(map)) << "no map from an interrupted grid";
  EXPECT_NEAR(r.tool_z_mm, host::defaults::kZUpMm, 0.01) << "the tool up";
}

// `send --probe` interrupted (SIGTERM) while it probes: the same lift and exit 5 as `probe`,
// nothing of the job sent.
TEST(ProbeCli, SendProbeInterruptedRaisesTheToolAndExitsLikeProbe) {
  const std::string map = temp_map("send_probe_interrupt");
  const Interrupted r = interrupt_first_descent(
      {"send", kWord, "--to", "TO", "--probe", "--height-map", map}, signal(SIGTERM));
  EXPECT_EQ(r.code, 5) << "-1: still probing 10 s after SIGTERM";
  EXPECT_LT(r.took_s, 8.0);
  EXPECT_FALSE(std::filesystem::exists(map)) << "no map from an interrupted grid";
  EXPECT_NEAR(r.tool_z_mm, host::defaults::kZUpMm, 0.01) << "the tool up";
}

// The link going silent in the middle of a touch (outside tester 24): after the silence
// limit, 10 s, the link is lost, exit 6 as the guide gives it for `probe` and `send --probe`
// (it was 5, "refused by the controller"), and no map is written.
TEST(ProbeCli, ALinkSilentWhileProbingIsALostLinkExit6) {
  for (const char* command : {"probe", "send"}) {
    SCOPED_TRACE(command);
    const std::string map = temp_map(std::string("probe_silent_") + command);
    std::vector<std::string> args = {command, kWord, "--to", "TO", "--height-map", map};
    if (std::string(command) == "send") args.push_back("--probe");
    const Interrupted r = interrupt_first_descent(
        args, [](pid_t, host::test::FreezingProxy& proxy) { proxy.freeze(true); }, 25);
    EXPECT_EQ(r.code, 6) << "-1: still waiting 25 s after the link froze";
    EXPECT_GE(r.took_s, 9.5);
    EXPECT_FALSE(std::filesystem::exists(map));
  }
}

}  // namespace
