// The serial link: the simulated machine behind a pseudo-terminal (socat bridges a pty to
// its TCP port), streamed at 115200 Bd through host::open_link("serial:...").
#include <gtest/gtest.h>

#include <signal.h>    // kill
#include <sys/wait.h>  // waitpid
#include <unistd.h>    // fork, execlp

#include <atomic>      // std::atomic
#include <filesystem>  // std::filesystem
#include <thread>      // std::thread

#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

bool have_socat() {
  return std::system("command -v socat >/dev/null 2>&1") == 0;
}

TEST(SerialLink, JobCompletesThroughAPtyAt115200) {
  if (!have_socat()) GTEST_SKIP() << "socat not installed (scripts/bootstrap.sh installs it)";
  const JobPlan plan = test::plan_of(test::drawing_of({test::circle_curve(15, 15, 5)}));
  sim::SimMachine machine{sim::SimOptions{}};
  sim::ServerOptions so;
  so.port = 0;
  sim::SimServer server(machine, so);
  test::Serving serving(server);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("engraver-pty-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string tty = (dir / "tty").string();
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string pty = "PTY,link=" + tty + ",raw,echo=0";
    const std::string tcp = "TCP:127.0.0.1:" + std::to_string(server.port());
    execlp("socat", "socat", pty.c_str(), tcp.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 200 && !std::filesystem::exists(tty); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  JobOutcome outcome = JobOutcome::kLinkLost;
  std::string message = "socat did not create " + tty;
  if (std::filesystem::exists(tty)) {
    auto link =
        open_link(parse_link_spec("serial:" + tty + ",115200"), std::chrono::milliseconds(2000));
    SenderOptions o;
    o.status_interval = std::chrono::milliseconds(5);
    Sender sender(*link, o);
    sender.open_session();
    outcome = sender.run(encode_job(plan, EncodeOptions{}), nullptr);
    message = sender.message();
  }
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  serving.stop();
  std::filesystem::remove_all(dir);
  EXPECT_EQ(outcome, JobOutcome::kCompleted) << message;
}

}  // namespace
}  // namespace host
