// SimJobOptions::before_job: commands sent after the session opens and before the job (the
// height map), the sender usable meanwhile (probing), neither counted as the job's.
#include <gtest/gtest.h>

#include "firmware/protocol/messages.h"
#include "host/lib/sim/sim_job.h"
#include "host/lib/stream/encode_command.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

TEST(SimJobBeforeJob, ItsCommandsRunFirstAndAreNotCountedAsTheJobs) {
  const JobPlan plan = test::plan_of(test::drawing_of({test::line_curve(0, 0, 10, 0)}));
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(2);
  const sim::SimJobResult plain = sim::run_sim_job(plan, o);
  ASSERT_EQ(plain.outcome, JobOutcome::kCompleted) << plain.message;

  bool sender_answered = false;
  o.before_job = [&](Sender& sender) {
    sender.read_status();  // the session is open: the sender talks (a throw would end the run)
    sender_answered = true;
    proto::DwellCmd dwell{};
    dwell.dwell_ms = 3000;
    return std::vector<QueuedCommand>{encode_command(dwell)};
  };
  const sim::SimJobResult with = sim::run_sim_job(plan, o);
  ASSERT_EQ(with.outcome, JobOutcome::kCompleted) << with.message;
  EXPECT_TRUE(sender_answered);
  EXPECT_EQ(with.setup.commands, 1u);
  EXPECT_GT(with.setup.wire_bytes, 0u);
  EXPECT_EQ(with.commands, plain.commands);
  EXPECT_EQ(with.wire_bytes, plain.wire_bytes);
  // The dwell ran before the job: the machine time grew by it.
  EXPECT_GE(with.virtual_ms, plain.virtual_ms + 2900);
}

}  // namespace
}  // namespace host
