// The simulator served to other programs: its clock (fast while the host talks, the wall
// clock's pace while it is silent) and serving on a pseudo-terminal instead of TCP.
#include <gtest/gtest.h>

#include <poll.h>    // poll
#include <pty.h>     // openpty
#include <unistd.h>  // read, write, close

#include <chrono>  // steady_clock
#include <thread>  // sleep_for

#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/encode_command.h"  // encode_command
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/served_sim.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using std::chrono::milliseconds;

// The host end of a pty pair as a Link.
class PtyLink : public Link {
 public:
  explicit PtyLink(int fd) : fd_(fd) {}
  void write(const uint8_t* data, size_t size) override {
    while (size > 0) {
      const ssize_t n = ::write(fd_, data, size);
      if (n <= 0) throw LinkError("pty write failed");
      data += n;
      size -= static_cast<size_t>(n);
    }
  }
  size_t read(uint8_t* buffer, size_t capacity, milliseconds timeout) override {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return 0;
    const ssize_t n = ::read(fd_, buffer, capacity);
    return n > 0 ? static_cast<size_t>(n) : 0;
  }
  std::string name() const override { return "pty"; }

 private:
  int fd_;
};

TEST(SimServer, ServesAJobOnAPseudoTerminal) {
  int master = -1, slave = -1;
  char name[256] = {};
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
  sim::SimMachine machine{sim::SimOptions{}};
  sim::ServerOptions so;
  so.device = name;
  sim::SimServer server(machine, so);
  ::close(slave);  // the server opened its own
  EXPECT_EQ(server.port(), 0);
  test::Serving serving(server);
  PtyLink link(master);
  SenderOptions o;
  o.status_interval = milliseconds(5);
  Sender sender(link, o);
  sender.open_session();
  const JobPlan plan = test::plan_of(test::drawing_of({test::circle_curve(15, 15, 5)}));
  const JobOutcome outcome = sender.run(encode_job(plan, EncodeOptions{}), nullptr);
  serving.stop();
  ::close(master);
  EXPECT_EQ(outcome, JobOutcome::kCompleted) << sender.message();
}

// The sender's verdict counts in the project's words: one command, not "1 commands".
TEST(SimServer, ASenderNamesOneCommandInTheSingular) {
  test::ServedSim served;
  auto link = open_link(parse_link_spec(served.address()), milliseconds(2000));
  SenderOptions o;
  o.status_interval = milliseconds(5);
  Sender sender(*link, o);
  const std::vector<QueuedCommand> one{encode_command(proto::RapidMoveCmd{1000, 0})};
  ASSERT_EQ(sender.run(one, nullptr), JobOutcome::kCompleted) << sender.message();
  EXPECT_EQ(sender.message(), "the 1 command executed");
  const std::vector<QueuedCommand> two(2, encode_command(proto::RapidMoveCmd{2000, 0}));
  ASSERT_EQ(sender.run(two, nullptr), JobOutcome::kCompleted) << sender.message();
  EXPECT_EQ(sender.message(), "all 2 commands executed");
}

TEST(SimServer, MachineTimeFollowsTheWallClockWhileTheHostIsSilent) {
  // Connected, then silent for 1 s of wall time: the machine may run ahead only by the fast
  // window, so 1.0-1.5 s of machine time pass (the old rule gave 0.68 s), and the link
  // watchdog (2 s) has not tripped.
  test::ServedSim served;
  auto link = open_link(parse_link_spec(served.address()), milliseconds(2000));
  Sender sender(*link, SenderOptions{});
  sender.open_session();
  const uint64_t t0 = served.machine.now_ms();
  const auto w0 = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(milliseconds(1000));
  const uint64_t t1 = served.machine.now_ms();
  const double wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - w0).count();
  served.stop();
  const double machine_ms = static_cast<double>(t1 - t0);
  EXPECT_GT(machine_ms, wall_ms - 250) << "machine time fell behind the wall clock";
  EXPECT_LT(machine_ms, wall_ms + 500 + 250) << "machine time ran ahead of the wall clock";
}

}  // namespace
}  // namespace host
