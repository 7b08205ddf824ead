// A host that vanishes mid-job: the machine must come to a controlled stop by itself (link
// watchdog), and a new connection must find it stopped and able to start a fresh session.
#include <gtest/gtest.h>

#include <atomic>  // std::atomic
#include <thread>  // std::thread

#include "host/lib/sim/sim_job.h"
#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

TEST(LinkWatchdog, MachineStopsWhenTheHostDisappearsAndANewSessionFindsItStopped) {
  const JobPlan plan = test::plan_of(test::drawing_of(
      {test::circle_curve(20, 20, 10), test::circle_curve(50, 20, 10), test::s_curve(70, 20)}));
  sim::SimMachine machine{sim::SimOptions{}};
  sim::ServerOptions so;
  so.port = 0;
  sim::SimServer server(machine, so);
  test::Serving serving(server);

  LinkSpec spec;
  spec.host = "127.0.0.1";
  spec.port = server.port();
  JobOutcome outcome = JobOutcome::kCompleted;
  {
    auto link = open_link(spec, std::chrono::milliseconds(2000));
    SenderOptions o;
    o.status_interval = std::chrono::milliseconds(2);
    Sender sender(*link, o);
    sender.open_session();
    try {
      // The host vanishes once the machine is cutting: the first command has run.
      outcome = sender.run(encode_job(plan, EncodeOptions{}), [](const Progress& p) {
        if (p.executed >= 4) throw LinkError("test: host gone");
      });
    } catch (const LinkError&) {
      outcome = JobOutcome::kLinkLost;
    }
  }  // the TCP connection closes here
  EXPECT_EQ(outcome, JobOutcome::kLinkLost);

  // Reconnect: the machine has stopped on its own (nobody told it to).
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  auto link = open_link(spec, std::chrono::milliseconds(2000));
  SenderOptions o;
  o.status_interval = std::chrono::milliseconds(2);
  Sender second(*link, o);
  second.open_session();
  // The new session stops what was left; give the deceleration time to end (the machine
  // follows the wall clock once the host is silent) before checking that nothing moves.
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  serving.stop();

  // Stopped: two more seconds of machine time move nothing.
  const size_t samples = machine.trace().size();
  for (int ms = 0; ms < 2000; ++ms) machine.step_ms();
  EXPECT_EQ(machine.trace().size(), samples);
  const auto& trace = machine.trace();
  double cut = 0;
  const std::vector<bool> down = sim::pen_down_samples(trace, plan);
  for (size_t i = 1; i < trace.size(); ++i) {
    if (down[i]) {
      cut += std::hypot(trace[i].x_mm - trace[i - 1].x_mm, trace[i].y_mm - trace[i - 1].y_mm);
    }
  }
  EXPECT_LT(cut, 0.9 * plan.cut_length_mm);
}

}  // namespace
}  // namespace host
