// A host that vanishes mid-job: the machine must come to a controlled stop by itself (link
// watchdog), and a new connection must find it stopped and able to start a fresh session.
#include <gtest/gtest.h>

#include <atomic>  // std::atomic
#include <thread>  // std::thread

#include "host/lib/sim/sim_job.h"
#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/faulty_link.h"
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
  std::atomic<bool> stop{false};
  std::thread serving([&] { server.run(stop); });

  LinkSpec spec;
  spec.host = "127.0.0.1";
  spec.port = server.port();
  JobOutcome outcome = JobOutcome::kCompleted;
  {
    test::Faults f;
    f.cut_after = 1500;  // the session, zeroing and part of the job get through
    test::FaultyLink link(open_link(spec, std::chrono::milliseconds(2000)), f);
    SenderOptions o;
    o.status_interval = std::chrono::milliseconds(2);
    Sender sender(link, o);
    sender.open_session();
    try {
      outcome = sender.run(encode_job(plan, EncodeOptions{}), nullptr);
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
  stop = true;
  serving.join();

  const auto& trace = machine.trace();
  ASSERT_FALSE(trace.empty());
  const uint64_t last_move_ms = trace.back().t_ms;
  // Stopped well before the end of the simulated time, and short of the whole job.
  EXPECT_LT(last_move_ms + 1000, machine.now_ms());
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
