// A host that vanishes mid-job: the machine must come to a controlled stop by itself (link
// watchdog), and a new connection must find it stopped and able to start a fresh session.
#include <gtest/gtest.h>

#include <atomic>  // std::atomic
#include <cstdio>  // std::printf
#include <thread>  // std::thread

#include "host/lib/sim/sim_job.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/cut_link.h"
#include "host_tests/host/sim/cut_path.h"
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
  const std::vector<bool> down = test::pen_down_samples(trace, plan);
  for (size_t i = 1; i < trace.size(); ++i) {
    if (down[i]) {
      cut += std::hypot(trace[i].x_mm - trace[i - 1].x_mm, trace[i].y_mm - trace[i - 1].y_mm);
    }
  }
  EXPECT_LT(cut, 0.9 * plan.cut_length_mm);
}

SenderOptions lockstep(sim::SimMachine& m) {
  SenderOptions o;
  o.clock = [&m] { return sim::machine_clock(m); };
  o.status_interval = std::chrono::milliseconds(50);
  return o;
}

// The job's tool path on the simulated machine, its link cut for `cut_ms` (0: never) once
// half its commands have run, and how it ended.
struct CutRun {
  JobOutcome outcome = JobOutcome::kCompleted;
  std::string message;
  std::vector<sim::ToolSample> trace;
  SenderStats stats;
  bool link_held = false;  // a status showed the link watchdog's hold
};

CutRun run_with_cut(const JobPlan& plan, uint32_t cut_ms) {
  sim::SimMachine m{sim::SimOptions{}};
  test::CutLink link(m);
  Sender s(link, lockstep(m));
  const proto::SessionReply caps = s.open_session();
  EncodeOptions enc;
  enc.max_payload = caps.max_payload;
  enc.controller = &caps;
  CutRun r;
  bool cut_done = false;
  r.outcome = s.run(encode_job(plan, enc), [&](const Progress& p) {
    if (cut_ms > 0 && !cut_done && p.total > 0 && p.executed * 2 >= p.total) {
      cut_done = true;
      link.cut_for(cut_ms);
    }
    if (p.status.flags & proto::kStatusLinkHold) r.link_held = true;
  });
  r.message = s.message();
  r.trace = m.trace();
  r.stats = s.stats();
  return r;
}

// Issue 25's workshop tester: a link cut for over 2 s mid-job (the controller holds the job
// by its link watchdog) left the sender waiting out its 30 s stall limit. When the link is
// back the job goes on (#R) and cuts the path an uncut run cuts, nothing twice.
TEST(LinkWatchdog, AJobHeldByALinkCutGoesOnWhenTheLinkIsBackAndCutsTheSamePath) {
  const JobPlan plan = test::plan_of(test::drawing_of(
      {test::circle_curve(20, 20, 10), test::circle_curve(50, 20, 10), test::s_curve(70, 20)}));
  const CutRun reference = run_with_cut(plan, 0);
  ASSERT_EQ(reference.outcome, JobOutcome::kCompleted) << reference.message;
  const CutRun cut = run_with_cut(plan, 3000);
  EXPECT_TRUE(cut.link_held) << "the cut was not long enough to hold the job";
  ASSERT_EQ(cut.outcome, JobOutcome::kCompleted) << cut.message;
  EXPECT_EQ(cut.stats.link_hold_resumes, 1u);
  const test::CutPath ref = test::cut_path(reference.trace, plan);
  const test::CutPath got = test::cut_path(cut.trace, plan);
  ASSERT_GT(ref.length_mm, 100.0);
  const double off_mm = test::max_distance_mm(got, ref),
               missed_mm = test::max_distance_mm(ref, got);
  std::printf("cut %.4f mm (uncut link %.4f mm); farthest from it %.4f mm, uncut %.4f mm\n",
              got.length_mm, ref.length_mm, off_mm, missed_mm);
  EXPECT_LT(off_mm, 0.005);
  EXPECT_LT(missed_mm, 0.005);
  EXPECT_NEAR(got.length_mm, ref.length_mm, 0.01);
  // It stood still while held: the cut run took the hold's time longer.
  EXPECT_GT(cut.trace.back().t_ms, reference.trace.back().t_ms + 1000);
}

}  // namespace
}  // namespace host
