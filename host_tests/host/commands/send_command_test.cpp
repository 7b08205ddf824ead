// `engraver send` as a function: the resume point's text, outcomes as exit codes, and a job
// streamed to the simulated machine in lockstep through send_job.
#include <gtest/gtest.h>

#include <fmt/format.h>  // fmt::format

#include <sstream>  // std::ostringstream

#include "firmware/protocol/wire_codes.h"  // proto::command_role
#include "host/lib/commands/exit_codes.h"
#include "host/lib/commands/send_command.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_machine.h"
#include "host_tests/host/sim/cut_path.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host::commands {
namespace {

const double kShortLiftMm = 0.2;  // short pen lifts: a short job in machine time

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
  EXPECT_EQ(parse_resume_at("2147483647").index, 2147483647);
}

TEST(SendCommandResumeAt, RefusesAnythingElseAsAUsageError) {
  // An outside tester's: 99999999999 wrapped to job command 1215752191; signs and blanks
  // went through on one side of the number.
  for (const char* bad : {"", "x", "-1", "12:", "12:-1", "12:65536", "12x", "12:40:1",
                          "99999999999", "2147483648", "+3", " 3", "3 ", "3:+4", "3: 4"})
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

// The exit code and message check_resume_at ends with ("" and 0 when it takes the point).
CommandFailure resume_at_refusal(const JobPlan& plan, const std::string& text) {
  try {
    check_resume_at(plan, EncodeOptions{}, parse_resume_at(text));
  } catch (const CommandFailure& e) {
    return e;
  }
  return CommandFailure(kExitOk, "");
}

// An outside tester's --resume-at 100000 on a job of 111 commands was refused only after
// connecting (exit 1, "the job has no such command"): now on the plan, exit 2, with the count.
TEST(SendCommandResumeAt, AnIndexBeyondTheJobIsABadCommandLineNamingTheCount) {
  const JobPlan plan = two_lines();
  const EncodedJobSummary job = summarize_job(plan, EncodeOptions{});
  const size_t last = job.job_commands - 1;
  EXPECT_EQ(resume_at_refusal(plan, std::to_string(last)).code, kExitOk);
  for (const std::string beyond : {std::to_string(last + 1), std::string("100000")}) {
    const CommandFailure e = resume_at_refusal(plan, beyond);
    EXPECT_EQ(e.code, kExitUsage) << beyond;
    EXPECT_EQ(std::string(e.what()),
              fmt::format("--resume-at: '{}': this job has {} job commands (INDEX 0 .. {}) of its "
                          "{} commands; a progress line's 'job {}' means the job had finished",
                          beyond, job.job_commands, last, job.commands, job.job_commands));
  }
}

TEST(SendCommandResumeAt, APointBeyondTheCurveIsABadCommandLine) {
  // One circle: job command 4 is its spline (the set-up and the moves to its start first), of
  // 121 curve points at the default tolerance.
  const JobPlan plan = test::plan_of(test::drawing_of({test::circle_curve(50, 50, 10)}));
  EXPECT_EQ(resume_at_refusal(plan, "4:120").code, kExitOk);
  const CommandFailure e = resume_at_refusal(plan, "4:60000");
  EXPECT_EQ(e.code, kExitUsage);
  EXPECT_STREQ(e.what(),
               "--resume-at: '4:60000': resume at job command 4: its curve has 121 points, not "
               "60001");
  // Job command 0 is not a curve: it has no points to resume from.
  const CommandFailure not_a_curve = resume_at_refusal(plan, "0:60000");
  EXPECT_EQ(not_a_curve.code, kExitUsage);
  EXPECT_STREQ(not_a_curve.what(),
               "--resume-at: '0:60000': job command 0 is not a curve (a move, a pause or a "
               "setting): it has no point 60000, only 0");
  EXPECT_EQ(resume_at_refusal(plan, "0:0").code, kExitOk);
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
  Progress last;
  o.on_progress = [&progress_calls, &last](const Progress& p) {
    ++progress_calls;
    last = p;
  };
  std::ostringstream log;
  const SendResult r = send_job(link, plan, o, log);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message << "\n" << log.str();
  // The last progress says the whole stream done (a progress line ended at 111/112).
  EXPECT_EQ(last.executed, r.commands);
  EXPECT_EQ(last.total, r.commands);
  // The first line counts as run's report does: the job's commands and the set-up apart.
  EXPECT_NE(log.str().find(fmt::format("{} commands (and 1 set-up command before the job: the "
                                       "height map or its clearing)",
                                       r.commands - 1)),
            std::string::npos)
      << log.str();
  EXPECT_EQ(attached, (std::vector<bool>{true, false}));
  EXPECT_EQ(streaming, 1);
  EXPECT_GT(progress_calls, 0u);
  EXPECT_FALSE(r.nothing_left);
  EXPECT_GT(r.commands, 0u);
  EXPECT_GT(r.stats.frames_sent, 0u);
  // The job id is the whole job's as the library encodes it for this controller.
  EXPECT_NE(r.job_id, 0);
  EXPECT_NE(log.str().find("two-lines.dxf -> simulated machine"), std::string::npos) << log.str();
  // The bytes are said to be the job's and the set-up's (an outside tester could not tell).
  EXPECT_NE(log.str().find(" bytes of frames for both (status queries and resends come on top)"),
            std::string::npos)
      << log.str();
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

// An outside tester's send --no-zero to a fresh simulator streamed the set-up and ended with
// exit 5 at the first move ("machine not zeroed"): the status says so before anything goes.
TEST(SendCommand, NoZeroRefusesAMachineThatIsNotZeroedBeforeSendingAnything) {
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  SendOptions o = lockstep_send(machine);
  o.sender.zero_first = false;  // --no-zero
  std::ostringstream log;
  try {
    send_job(link, two_lines(), o, log);
    FAIL() << "sent to a machine that is not zeroed\n" << log.str();
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitJobFailed);
    EXPECT_STREQ(e.what(),
                 "the machine is not zeroed and --no-zero does not start manual zeroing: nothing "
                 "was sent (without --no-zero, send starts it: jog to the corner with the "
                 "joystick and press confirm)");
  }
  // Nothing of the job reached the controller: no job mark (#J) was stored.
  Sender check(link, o.sender);
  check.open_session();
  EXPECT_EQ(check.read_status().flags & proto::kStatusJob, 0);
}

TEST(SendCommand, NoZeroSendsToAZeroedMachine) {
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  SendOptions o = lockstep_send(machine);
  std::ostringstream log;
  ASSERT_EQ(send_job(link, two_lines(), o, log).outcome, JobOutcome::kCompleted) << log.str();
  o.sender.zero_first = false;  // zeroed by the first job's manual zeroing
  EXPECT_EQ(send_job(link, two_lines(), o, log).outcome, JobOutcome::kCompleted) << log.str();
}

// Zeroing a machine that is not zeroed leaves a plain line in send's log (an outside
// tester: with stderr not a terminal nothing said the machine was zeroed, the simulated
// operator confirming before any status showed "zeroing"); a zeroed machine gets none.
TEST(SendCommand, ZeroingTheMachineLeavesALineInTheLog) {
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  const SendOptions o = lockstep_send(machine);
  const std::string line =
      "engraver: zeroed the machine (#M): its zero is the tool's position when the zeroing was "
      "confirmed\n";
  std::ostringstream first;
  ASSERT_EQ(send_job(link, two_lines(), o, first).outcome, JobOutcome::kCompleted) << first.str();
  EXPECT_NE(first.str().find(line), std::string::npos) << first.str();
  std::ostringstream second;
  ASSERT_EQ(send_job(link, two_lines(), o, second).outcome, JobOutcome::kCompleted);
  EXPECT_EQ(second.str().find("zeroed the machine"), std::string::npos) << second.str();
}

TEST(SendCommand, HoldsOnlyTheSendersWindowWhateverTheJobsLength) {
  // 600 lines: ~2 400 commands; send keeps what is in flight and the 128 before it.
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  std::ostringstream log;
  const SendResult r =
      send_job(link, test::separate_lines(600, kShortLiftMm), lockstep_send(machine), log);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message << "\n" << log.str();
  EXPECT_GT(r.commands, 2400u);
  EXPECT_GT(r.commands_held_max, 0u);
  EXPECT_LE(r.commands_held_max, 128u + 64u);
}

JobPlan three_curves() {
  return test::plan_of(test::drawing_of(
      {test::circle_curve(20, 20, 10), test::s_curve(40, 20), test::circle_curve(75, 20, 8)}));
}

// Job command index of the plan's nth spline header.
int32_t job_index_of_spline(const JobPlan& plan, int nth) {
  int32_t job = 0;
  int n = 0;
  for (const QueuedCommand& c : encode_job(plan, EncodeOptions{})) {
    if (c.letter == proto::kCmdSplineHeader && n++ == nth) return job;
    if (proto::command_role(c.letter) == proto::CommandRole::kJobCommand) ++job;
  }
  return -1;
}

TEST(SendCommand, ResumesAStreamedJobFromTheMiddleAndCutsTheSamePath) {
  const JobPlan plan = three_curves();
  std::vector<sim::ToolSample> reference;
  {
    sim::SimMachine machine{sim::SimOptions{}};
    sim::SimLink link(machine);
    std::ostringstream log;
    ASSERT_EQ(send_job(link, plan, lockstep_send(machine), log).outcome, JobOutcome::kCompleted);
    reference = machine.trace();
  }
  // The link is cut part way along the S curve; the machine's watchdog holds the job.
  sim::SimMachine machine{sim::SimOptions{}};
  const int32_t s_curve = job_index_of_spline(plan, 1);
  {
    sim::SimLink link(machine);
    SendOptions o = lockstep_send(machine);
    o.on_progress = [s_curve](const Progress& p) {
      if ((p.status.flags & proto::kStatusJob) && p.status.job_index == s_curve &&
          p.status.curve_point >= 5)
        throw LinkError("test: link cut");
    };
    std::ostringstream log;
    EXPECT_THROW(send_job(link, plan, o, log), LinkError);
  }
  for (int ms = 0; ms < 4000; ++ms) machine.step_ms();
  sim::SimLink link(machine);
  SendOptions o = lockstep_send(machine);
  o.resume = true;
  std::ostringstream log;
  const SendResult r = send_job(link, plan, o, log);
  ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message << "\n" << log.str();
  EXPECT_NE(log.str().find(fmt::format("resuming at job command {} of", s_curve)),
            std::string::npos)
      << log.str();
  EXPECT_NE(log.str().find("cut short"), std::string::npos) << log.str();
  // Every point cut lies on the uninterrupted path, all of it was cut, nothing twice.
  const test::CutPath ref = test::cut_path(reference, plan);
  const test::CutPath got = test::cut_path(machine.trace(), plan);
  ASSERT_GT(ref.length_mm, 100.0);
  EXPECT_LT(test::max_distance_mm(got, ref), 0.010);
  EXPECT_LT(test::max_distance_mm(ref, got), 0.010);
  EXPECT_NEAR(got.length_mm, ref.length_mm, 0.02);
}

}  // namespace
}  // namespace host::commands
