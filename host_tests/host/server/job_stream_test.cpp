// The workshop's job stream: the sender's cursor and the progress cursor over the plan
// encoded as they go give what the whole list gives (plan step, first uncut curve), and hold
// a window of the job, not the job.
#include <gtest/gtest.h>

#include <algorithm>  // std::max

#include "host/lib/server/job_stream.h"
#include "host/lib/server/progress_saver.h"  // first_uncut_curve
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host::server {
namespace {

// The step of the first command at or after i that has one, in the whole list.
int step_from(const std::vector<QueuedCommand>& list, size_t i) {
  for (; i < list.size(); ++i)
    if (list[i].step >= 0) return list[i].step;
  return -1;
}

// The sender's pattern: reads ahead, lets go of what is stored; the progress asks about
// commands 100 behind it.
void walk(JobStream& stream, const std::vector<QueuedCommand>& whole) {
  ASSERT_EQ(stream.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i) {
    const QueuedCommand& c = stream.source().at(i);
    ASSERT_EQ(c.payload, whole[i].payload) << i;
    if (i >= 128) stream.source().release_before(i - 128);
    if (i % 7 == 0 && i >= 100) {
      EXPECT_EQ(stream.step_from(i - 100), step_from(whole, i - 100)) << i;
      EXPECT_EQ(stream.first_uncut_curve(i - 100), first_uncut_curve(whole, i - 100)) << i;
    }
  }
  EXPECT_EQ(stream.first_uncut_curve(whole.size()), -1);
}

TEST(JobStream, FollowsTheWholeListHoldingOnlyAWindow) {
  const JobPlan plan = test::separate_lines(2000);  // ~8 000 commands
  const EncodeOptions enc;
  std::vector<QueuedCommand> whole = encode_job(plan, enc);
  JobStream stream(plan, enc);
  EXPECT_EQ(stream.job_id(), job_id_of(whole));
  const std::vector<QueuedCommand> map{whole[1]};  // any set-up frame
  stream.set_setup(map);
  whole.insert(whole.begin(), map.begin(), map.end());
  EXPECT_EQ(stream.wire_bytes(), wire_bytes(whole));
  walk(stream, whole);
  EXPECT_GT(whole.size(), 8000u);
  EXPECT_LE(stream.held_max(), 200u);
}

TEST(JobStream, AContinuedJobStartsAtItsPrefixAfterTheMap) {
  const JobPlan plan = test::separate_lines(300);
  const EncodeOptions enc;
  const std::vector<QueuedCommand> whole = encode_job(plan, enc);
  const size_t from = whole.size() / 2;
  const std::vector<QueuedCommand> prefix{whole[2], whole[3]};
  const std::vector<QueuedCommand> map{whole[1]};
  JobStream stream(plan, enc);
  stream.start_at(from, prefix);
  stream.set_setup(map);
  std::vector<QueuedCommand> expected = map;
  expected.insert(expected.end(), prefix.begin(), prefix.end());
  expected.insert(expected.end(), whole.begin() + static_cast<long>(from), whole.end());
  EXPECT_EQ(stream.job_id(), job_id_of(whole));  // the whole job's
  EXPECT_EQ(stream.wire_bytes(), wire_bytes(expected));
  walk(stream, expected);
}

}  // namespace
}  // namespace host::server
