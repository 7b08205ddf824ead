// A resume of a streamed job: the prefix found in a pass over the plan encoded again, then
// the job from the resume point encoded as the sender goes, is the stream a resume of the
// whole list gives, at every job command (no list of the job is held).
#include <gtest/gtest.h>

#include "host/lib/stream/command_source.h"
#include "host/lib/stream/job_resume.h"

namespace host {
namespace {

PlanStep step_of(PlanStep::Kind kind) {
  PlanStep s;
  s.kind = kind;
  return s;
}

// Spindle on and its run-up, a straight cut with a tool offset (a degree-1 spline), a cut,
// a drill cycle, a pause, the spindle off: every kind of set-up a resume restores.
JobPlan mixed_plan() {
  JobPlan plan;
  PlanStep on = step_of(PlanStep::kSpindle);
  on.spindle_on = true;
  PlanStep dwell = step_of(PlanStep::kDwell);
  dwell.dwell_ms = 1500;
  PlanStep up = step_of(PlanStep::kPenUp);
  up.z_um = 2000;
  PlanStep rapid = step_of(PlanStep::kRapid);
  rapid.to = {5000, 5000};
  PlanStep down = step_of(PlanStep::kPenDown);
  down.z_um = -100;
  down.feed_um_per_s = 500;
  PlanStep offset_cut = step_of(PlanStep::kFeed);
  offset_cut.to = {25000, 5000};
  offset_cut.feed_um_per_s = 5000;
  offset_cut.tool_offset_um = 300;
  offset_cut.curve = 0;
  PlanStep cut = step_of(PlanStep::kFeed);
  cut.to = {25000, 20000};
  cut.feed_um_per_s = 5000;
  cut.curve = 1;
  PlanStep drill = step_of(PlanStep::kDrill);
  drill.to = {30000, 30000};
  drill.z_start_um = 1000;
  drill.z_um = -1800;
  drill.feed_um_per_s = 700;
  drill.curve = 2;
  PlanStep pause = step_of(PlanStep::kPause);
  pause.set_text("done");
  PlanStep off = step_of(PlanStep::kSpindle);
  plan.steps = {on, dwell, up, rapid, down, offset_cut, cut, up, drill, pause, up, off};
  return plan;
}

void expect_same_commands(EncodedJob& streamed, const std::vector<QueuedCommand>& whole,
                          const std::string& what) {
  ASSERT_EQ(streamed.size(), whole.size()) << what;
  for (size_t i = 0; i < whole.size(); ++i) {
    const QueuedCommand& c = streamed.at(i);
    EXPECT_EQ(c.letter, whole[i].letter) << what << " command " << i;
    EXPECT_EQ(c.payload, whole[i].payload) << what << " command " << i;
    EXPECT_EQ(c.step, whole[i].step) << what << " command " << i;
    streamed.release_before(i + 1);
  }
}

TEST(StreamedResume, EveryJobCommandResumesAsTheWholeListDoes) {
  const JobPlan plan = mixed_plan();
  EncodeOptions enc;
  enc.title = "mixed";
  const std::vector<QueuedCommand> whole = encode_job(plan, enc);
  const uint16_t id = job_id_of(whole);
  const JobPass pass = pass_over(plan, enc, id);
  int32_t job_commands = 0;
  for (const QueuedCommand& c : whole)
    job_commands += proto::command_role(c.letter) == proto::CommandRole::kJobCommand;
  ASSERT_GT(job_commands, 10);
  for (int32_t index = 0; index <= job_commands; ++index) {
    const std::string what = "job command " + std::to_string(index);
    ResumePoint at;
    if (index < job_commands) {
      at = resume_point_at(pass, index, 0, 0);
      const ResumePoint listed = resume_point_at(whole, index, 0, 0);
      EXPECT_EQ(at.x_um, listed.x_um) << what;
      EXPECT_EQ(at.y_um, listed.y_um) << what;
      EXPECT_EQ(at.job_id, id) << what;
      EXPECT_EQ(describe_resume_point(pass, at), describe_resume_point(whole, at)) << what;
    } else {
      at.job_index = index;  // past the end: the job finished
    }
    const std::vector<QueuedCommand> expected = resume_commands(whole, at, enc);
    size_t from = 0;
    std::vector<QueuedCommand> prefix = resume_prefix(pass, at, enc, &from);
    EncodedJob streamed(plan, enc);
    if (prefix.empty()) {
      EXPECT_TRUE(expected.empty()) << what;
      EXPECT_EQ(from, whole.size()) << what;
      continue;
    }
    EXPECT_EQ(whole[from].letter, expected[prefix.size()].letter) << what;
    streamed.set_setup(std::move(prefix));
    streamed.start_at(from);
    expect_same_commands(streamed, expected, what);
  }
}

TEST(StreamedResume, AContinuedCurveIsFoundInAPassOverThePlan) {
  const JobPlan plan = mixed_plan();
  const EncodeOptions enc;
  const std::vector<QueuedCommand> whole = encode_job(plan, enc);
  const JobPass pass = pass_over(plan, enc, job_id_of(whole));
  const int32_t drill = job_index_of_curve(pass, 2);
  EXPECT_EQ(whole[command_of_job_index(whole, drill)].letter, proto::kCmdDrill);
  EXPECT_THROW(job_index_of_curve(pass, 7), PlanError);
}

}  // namespace
}  // namespace host
