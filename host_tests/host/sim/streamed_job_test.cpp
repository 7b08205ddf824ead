// The run path streams a job: the plan is encoded as the sender goes and the sender lets go
// of what the controller has stored, so what is held does not grow with the job.
#include <gtest/gtest.h>

#include "host/lib/sim/sim_job.h"
#include "host/lib/stream/command_source.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

const double kShortLiftMm = 0.2;  // short pen lifts: a short job in machine time

TEST(StreamedJob, EncodesTheSameCommandsAsTheWholeList) {
  const JobPlan plan = test::separate_lines(50, kShortLiftMm);
  EncodeOptions enc;
  enc.title = "lines";
  const std::vector<QueuedCommand> whole = encode_job(plan, enc);
  EncodedJob streamed(plan, enc);
  EXPECT_EQ(streamed.summary().commands, whole.size());
  EXPECT_EQ(streamed.summary().job_id, job_id_of(whole));
  EXPECT_EQ(streamed.summary().wire_bytes, wire_bytes(whole));
  ASSERT_EQ(streamed.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i) {
    const QueuedCommand& c = streamed.at(i);
    EXPECT_EQ(c.letter, whole[i].letter) << i;
    EXPECT_EQ(c.payload, whole[i].payload) << i;
    EXPECT_EQ(c.step, whole[i].step) << i;
    streamed.release_before(i + 1);
  }
  EXPECT_LE(streamed.held(), 1u);
}

TEST(StreamedJob, SenderHoldsOnlyItsWindowWhateverTheJobsLength) {
  // 600 lines: ~2 400 commands. The sender may keep what is in flight (at most a queue's
  // worth) and the 128 before it, not the job.
  const JobPlan plan = test::separate_lines(600, kShortLiftMm);
  sim::SimJobOptions o;
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_GT(r.commands, 2400u);
  EXPECT_GT(r.commands_held_max, 0u);
  EXPECT_LE(r.commands_held_max, 128u + 64u);
}

}  // namespace
}  // namespace host
