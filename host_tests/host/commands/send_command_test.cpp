// `engraver send` as a function: the resume point's text, outcomes as exit codes, and a job
// streamed to the simulated machine in lockstep through send_job.
#include <gtest/gtest.h>

#include <sstream>  // std::ostringstream

#include "host/lib/commands/exit_codes.h"
#include "host/lib/commands/send_command.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_machine.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host::commands {
namespace {

int exit_code_of_resume_at(const std::string& text) {
  try {
    parse_resume_at(text);
  } catch (const CommandFailure& e) {
    return e.code;
  }
  return kExitOk;
}

TEST(SendCommandResumeAt, ReadsIndexAndOptionalPoint) {
  const ResumeAt a = parse_resume_at("12");
  EXPECT_EQ(a.index, 12);
  EXPECT_EQ(a.point, 0);
  const ResumeAt b = parse_resume_at("12:40");
  EXPECT_EQ(b.index, 12);
  EXPECT_EQ(b.point, 40);
  EXPECT_EQ(parse_resume_at("0:65535").point, 65535);
}

TEST(SendCommandResumeAt, RefusesAnythingElseAsAUsageError) {
  for (const char* bad : {"", "x", "-1", "12:", "12:-1", "12:65536", "12x", "12:40:1"})
    EXPECT_EQ(exit_code_of_resume_at(bad), kExitUsage) << "'" << bad << "'";
}

TEST(SendCommand, OutcomesEndWithTheirDocumentedExitCodes) {
  EXPECT_EQ(exit_code_of(JobOutcome::kCompleted), 0);
  EXPECT_EQ(exit_code_of(JobOutcome::kAborted), 3);
  EXPECT_EQ(exit_code_of(JobOutcome::kAlarm), 4);
  EXPECT_EQ(exit_code_of(JobOutcome::kRejected), 5);
  EXPECT_EQ(exit_code_of(JobOutcome::kLinkLost), 6);
  EXPECT_EQ(exit_code_of(JobOutcome::kStalled), 7);
}

// The sender on the simulated machine's clock, polling as send does.
SendOptions lockstep_send(sim::SimMachine& m) {
  SendOptions o;
  o.file = "two-lines.dxf";
  o.sender.clock = [&m] { return sim::machine_clock(m); };
  o.sender.status_interval = std::chrono::milliseconds(250);
  return o;
}

JobPlan two_lines() {
  return test::plan_of(
      test::drawing_of({test::line_curve(0, 0, 10, 0), test::line_curve(20, 5, 20, 15)}));
}

TEST(SendCommand, StreamsTheJobAndAttachesTheControlsOnlyWhileItRuns) {
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  const JobPlan plan = two_lines();
  SendOptions o = lockstep_send(machine);
  std::vector<bool> attached;  // true: a sender attached, false: detached
  o.attach_controls = [&attached](Sender* s) { attached.push_back(s != nullptr); };
  int streaming = 0;
  o.while_streaming = [&streaming](Sender&) {
    ++streaming;
    return std::shared_ptr<void>();
  };
  size_t progress_calls = 0;
  o.on_progress = [&progress_calls](const Progress&) { ++progress_calls; };
  std::ostringstream log;
  const SendResult r = send_job(link, plan, o, log);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message << "\n" << log.str();
  EXPECT_EQ(attached, (std::vector<bool>{true, false}));
  EXPECT_EQ(streaming, 1);
  EXPECT_GT(progress_calls, 0u);
  EXPECT_FALSE(r.nothing_left);
  EXPECT_GT(r.commands, 0u);
  EXPECT_GT(r.stats.frames_sent, 0u);
  // The job id is the whole job's as the library encodes it for this controller.
  EXPECT_NE(r.job_id, 0);
  EXPECT_NE(log.str().find("two-lines.dxf -> simulated machine"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("job completed"), std::string::npos) << log.str();
}

TEST(SendCommand, ResumeOnAControllerThatRanNoJobIsRefusedWithoutStreaming) {
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  SendOptions o = lockstep_send(machine);
  o.resume = true;
  std::vector<bool> attached;
  o.attach_controls = [&attached](Sender* s) { attached.push_back(s != nullptr); };
  std::ostringstream log;
  try {
    send_job(link, two_lines(), o, log);
    FAIL() << "resumed a job the controller never ran";
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitJobFailed);
    EXPECT_NE(std::string(e.what()).find("--resume-at"), std::string::npos) << e.what();
  }
  EXPECT_EQ(attached, (std::vector<bool>{true, false}));  // detached on the way out too
}

}  // namespace
}  // namespace host::commands
