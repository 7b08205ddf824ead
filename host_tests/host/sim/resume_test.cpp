// send --resume on the simulated machine: a job whose link is cut (or that is aborted) in the
// middle of a curve, continued from the controller's status, cuts the same path as a run that
// was never interrupted, and cuts no part of it twice. In lockstep (SimLink): deterministic.
#include <gtest/gtest.h>

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min, std::max
#include <cmath>      // std::hypot, std::floor
#include <cstdio>     // std::printf
#include <map>        // std::map
#include <optional>   // std::optional
#include <utility>    // std::pair

#include "firmware/protocol/codec.h"  // proto::decode
#include "host/lib/sim/sim_job.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/job_resume.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/cut_path.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using sim::SimLink;
using sim::SimMachine;
using sim::ToolSample;
using test::cut_path;
using test::CutPath;
using test::max_distance_mm;
using test::point_segment_mm;

SenderOptions lockstep(SimMachine& m) {
  SenderOptions o;
  o.clock = [&m] { return sim::machine_clock(m); };
  o.status_interval = std::chrono::milliseconds(50);
  return o;
}

std::vector<QueuedCommand> encode_for(const JobPlan& plan, const proto::SessionReply& caps) {
  EncodeOptions enc;
  enc.max_payload = caps.max_payload;
  enc.controller = &caps;
  return encode_job(plan, enc);
}

JobPlan test_plan() {
  return test::plan_of(test::drawing_of(
      {test::circle_curve(20, 20, 10), test::s_curve(40, 20), test::circle_curve(75, 20, 8)}));
}

// The same drawing with a 0.5 mm tool-radius offset on the left: the controller offsets, with
// arcs round convex corners and a lead-in to each offset start.
JobPlan offset_plan() {
  PlanOptions o;
  o.feed_mm_per_s = 10.0;
  o.margin_mm = 5.0;
  o.tool_side = ToolSide::kLeft;
  o.tool_radius_mm = 0.5;
  return plan_job(test::drawing_of({test::circle_curve(20, 20, 10), test::s_curve(40, 20),
                                    test::circle_curve(75, 20, 8)}),
                  o);
}

std::vector<ToolSample> uninterrupted(const JobPlan& plan) {
  SimMachine m{sim::SimOptions{}};
  SimLink link(m);
  Sender s(link, lockstep(m));
  const auto cmds = encode_for(plan, s.open_session());
  EXPECT_EQ(s.run(cmds, nullptr), JobOutcome::kCompleted) << s.message();
  return m.trace();
}

enum class Cut { kLinkLost, kAbort };

struct Interrupted {
  std::vector<ToolSample> trace;
  ResumePoint at;
  std::vector<QueuedCommand> job;
  size_t resume_commands = 0;
};

// Runs the job until the tool is on the given curve (job command), cuts it off, then resumes
// with a new sender as `send --resume` does.
// silent_ms: how long nobody talks to the machine before the resume (over 2 s: its link
// watchdog holds the job; shorter: the resume's #I finds it still cutting and stops it).
Interrupted interrupted(const JobPlan& plan, int nth_spline, Cut how, int min_point,
                        int silent_ms = 4000) {
  Interrupted r;
  SimMachine m{sim::SimOptions{}};
  std::vector<QueuedCommand> cmds;
  {
    SimLink link(m);
    Sender s(link, lockstep(m));
    cmds = encode_for(plan, s.open_session());
    // Job index of the nth #B.
    int32_t index = -1, n = 0, job = 0;
    for (const QueuedCommand& c : cmds) {
      if (c.letter == proto::kCmdSplineHeader && n++ == nth_spline) index = job;
      if (proto::command_role(c.letter) == proto::CommandRole::kJobCommand) ++job;
    }
    try {
      const JobOutcome o = s.run(cmds, [&](const Progress& p) {
        if ((p.status.flags & proto::kStatusJob) && p.status.job_index == index &&
            p.status.curve_point >= min_point) {
          if (how == Cut::kLinkLost) throw LinkError("test: link cut");
          s.request_abort();
        }
      });
      if (how == Cut::kLinkLost) ADD_FAILURE() << "the job ended before the cut: " << s.message();
      EXPECT_EQ(o, JobOutcome::kAborted);
    } catch (const LinkError&) {
    }
  }
  // Nobody talks to the machine: it cuts on until its link watchdog holds it (2 s).
  for (int ms = 0; ms < silent_ms; ++ms) m.step_ms();

  SimLink link(m);
  Sender s(link, lockstep(m));
  const proto::SessionReply caps = s.open_session();
  const std::optional<ResumePoint> at =
      resume_point_of(s.read_status_at_rest(std::chrono::seconds(10)));
  EXPECT_TRUE(at.has_value());
  if (!at) return r;
  r.at = *at;
  r.job = cmds;
  EXPECT_EQ(resume_mismatch(cmds, *at), "");  // the job the controller ran
  // The same drawing planned with another feed is another job: refused.
  const JobPlan slower =
      test::plan_of(test::drawing_of({test::circle_curve(20, 20, 10), test::s_curve(40, 20),
                                      test::circle_curve(75, 20, 8)}),
                    8.0);
  const std::vector<QueuedCommand> other = encode_for(slower, caps);
  // Both ids in decimal, as send's first line prints them (the tester saw hex here).
  EXPECT_EQ(resume_mismatch(other, *at),
            fmt::format("the controller's job (id {}) is not this one (id {}): resume with the "
                        "same file and the same plan options as the interrupted send",
                        at->job_id, job_id_of(other)));
  std::printf("resume at %s; tool at (%.3f, %.3f, %.3f) mm\n",
              describe_resume_point(cmds, *at).c_str(), at->x_um / 1000.0, at->y_um / 1000.0,
              at->z_um / 1000.0);
  const auto rest = resume_commands(cmds, *at, EncodeOptions{});
  r.resume_commands = rest.size();
  EXPECT_EQ(s.run(rest, nullptr), JobOutcome::kCompleted) << s.message();
  r.trace = m.trace();
  return r;
}

void expect_same_cut(const JobPlan& plan, const std::vector<ToolSample>& reference,
                     const Interrupted& run) {
  const CutPath ref = cut_path(reference, plan);
  const CutPath got = cut_path(run.trace, plan);
  ASSERT_GT(ref.length_mm, 100.0);
  const double off_mm = max_distance_mm(got, ref);
  const double missed_mm = max_distance_mm(ref, got);
  std::printf(
      "cut %.4f mm (uninterrupted %.4f mm); farthest from the uninterrupted path %.4f mm, "
      "uncut %.4f mm\n",
      got.length_mm, ref.length_mm, off_mm, missed_mm);
  // Every point cut lies on the uninterrupted path, and the whole path was cut.
  EXPECT_LT(off_mm, 0.010);
  EXPECT_LT(missed_mm, 0.010);
  // Nothing twice: a stretch cut again would add its length.
  EXPECT_NEAR(got.length_mm, ref.length_mm, 0.02);
}

TEST(SendResume, LinkCutMidCurveResumesAtTheCurvePointAndCutsTheSamePath) {
  const JobPlan plan = test_plan();
  const auto reference = uninterrupted(plan);
  const Interrupted run = interrupted(plan, 0, Cut::kLinkLost, 3);
  // The watchdog held the job part way round the first circle: cut short, mid-curve.
  EXPECT_TRUE(run.at.started);
  EXPECT_GT(run.at.curve_point, 3);
  expect_same_cut(plan, reference, run);
}

// The host comes back at once: the resume's #I stops the job mid-curve (decelerating along the
// path); the resume point is read once the machine is at rest.
TEST(SendResume, ResumedAtOnceWhileStillCuttingCutsTheSamePath) {
  const JobPlan plan = test_plan();
  const auto reference = uninterrupted(plan);
  const Interrupted run = interrupted(plan, 2, Cut::kLinkLost, 5, 0);
  EXPECT_TRUE(run.at.started);
  EXPECT_GT(run.at.curve_point, 5);
  expect_same_cut(plan, reference, run);
}

TEST(SendResume, ToolOffsetJobCutMidCurveResumesOnTheOffsetPath) {
  const JobPlan plan = offset_plan();
  const auto reference = uninterrupted(plan);
  const Interrupted run = interrupted(plan, 1, Cut::kLinkLost, 4);
  EXPECT_TRUE(run.at.started);
  EXPECT_GT(run.at.curve_point, 4);
  expect_same_cut(plan, reference, run);
}

// The tool stopped on the chord from the last curve point reached to the one it was heading
// for; the host computes both with the controller's curve walker (resume_point_at).
TEST(SendResume, TheToolStopsOnTheChordToTheReportedCurvePoint) {
  const JobPlan plan = test_plan();
  const Interrupted run = interrupted(plan, 0, Cut::kLinkLost, 3);
  ASSERT_GT(run.at.curve_point, 0);
  const ResumePoint from = resume_point_at(run.job, run.at.job_index, run.at.curve_point, 0);
  const ResumePoint to = resume_point_at(run.job, run.at.job_index, run.at.curve_point + 1, 0);
  EXPECT_EQ(from.curve_point, run.at.curve_point - 1);
  const CutPath::Seg chord{from.x_um / 1000.0, from.y_um / 1000.0, to.x_um / 1000.0,
                           to.y_um / 1000.0};
  const double chord_mm = std::hypot(chord.x1 - chord.x0, chord.y1 - chord.y0);
  EXPECT_GT(chord_mm, 0.0);
  EXPECT_LT(point_segment_mm(run.at.x_um / 1000.0, run.at.y_um / 1000.0, chord), 0.005);
}

TEST(SendResume, AbortMidCurveResumesAndCutsTheSamePath) {
  const JobPlan plan = test_plan();
  const auto reference = uninterrupted(plan);
  const Interrupted run = interrupted(plan, 1, Cut::kAbort, 10);
  EXPECT_TRUE(run.at.started);
  EXPECT_GE(run.at.curve_point, 10);
  expect_same_cut(plan, reference, run);
}

// A restarted controller remembers nothing: no job progress in its status, so send --resume
// has nothing to go on (the user resumes with --resume-at from the last status line).
TEST(SendResume, ARestartedControllerReportsNoJobProgress) {
  const JobPlan plan = test_plan();
  SimMachine first{sim::SimOptions{}};
  {
    SimLink link(first);
    Sender s(link, lockstep(first));
    const auto cmds = encode_for(plan, s.open_session());
    try {
      s.run(cmds, [&](const Progress& p) {
        if ((p.status.flags & proto::kStatusJobStarted) && p.status.job_index >= 4)
          throw LinkError("test: power cut");
      });
    } catch (const LinkError&) {
    }
    EXPECT_TRUE(resume_point_of(s.read_status()).has_value());
  }
  SimMachine restarted{sim::SimOptions{}};  // the same machine after a power cycle
  SimLink link(restarted);
  Sender s(link, lockstep(restarted));
  s.open_session();
  const proto::StatusReply st = s.read_status();
  EXPECT_FALSE(resume_point_of(st).has_value());
  EXPECT_EQ(st.flags & proto::kStatusZeroed, 0);
}

// Power cut mid-curve: the restarted machine is zeroed where the first one was (the simulated
// operator confirms at the power-on position, the same work zero) and the job resumes from the
// last status the host saw (--resume-at). The path is the same; what ran between that status
// and the power cut, up to one chord, is cut again.
TEST(SendResume, AfterARestartResumeAtTheLastStatusCutsTheSamePathRecuttingAtMostAChord) {
  const JobPlan plan = test_plan();
  const auto reference = uninterrupted(plan);
  SimMachine first{sim::SimOptions{}};
  std::vector<QueuedCommand> cmds;
  proto::StatusReply last{};
  {
    SimLink link(first);
    Sender s(link, lockstep(first));
    cmds = encode_for(plan, s.open_session());
    try {
      s.run(cmds, [&](const Progress& p) {
        last = p.status;
        if ((p.status.flags & proto::kStatusJobStarted) && p.status.job_index == 8 &&
            p.status.curve_point >= 20)
          throw LinkError("test: power cut");
      });
    } catch (const LinkError&) {
    }
  }
  ASSERT_EQ(command_of_job_index(cmds, last.job_index), command_of_job_index(cmds, 8));
  ASSERT_EQ(cmds[command_of_job_index(cmds, 8)].letter, proto::kCmdSplineHeader);
  SimMachine second{sim::SimOptions{}};
  SimLink link(second);
  Sender s(link, lockstep(second));
  s.open_session();
  const ResumePoint at = resume_point_at(cmds, last.job_index, last.curve_point, 0);
  EXPECT_EQ(s.run(resume_commands(cmds, at, EncodeOptions{}), nullptr), JobOutcome::kCompleted)
      << s.message();
  CutPath got = cut_path(first.trace(), plan);
  const CutPath after = cut_path(second.trace(), plan);
  got.segs.insert(got.segs.end(), after.segs.begin(), after.segs.end());
  got.length_mm += after.length_mm;
  const CutPath ref = cut_path(reference, plan);
  const double off_mm = max_distance_mm(got, ref);
  const double missed_mm = max_distance_mm(ref, got);
  std::printf("restart: cut %.4f mm (uninterrupted %.4f mm); farthest off %.4f mm, uncut %.4f mm\n",
              got.length_mm, ref.length_mm, off_mm, missed_mm);
  EXPECT_LT(off_mm, 0.010);
  EXPECT_LT(missed_mm, 0.010);
  // Recut: from the last curve point reached at that status to where the power went.
  EXPECT_GE(got.length_mm, ref.length_mm - 0.02);
  EXPECT_LT(got.length_mm, ref.length_mm + 1.0);
}

TEST(SendResume, ResumeStreamLiftsTravelsPlungesThenMarksAndSendsTheRest) {
  const JobPlan plan = test_plan();
  const auto cmds = encode_job(plan, EncodeOptions{});
  const size_t b = command_of_job_index(cmds, 4);
  ASSERT_EQ(cmds[b].letter, proto::kCmdSplineHeader);
  ResumePoint at;
  at.job_index = 4;
  at.curve_point = 17;
  at.started = true;
  at.x_um = 12345;
  at.y_um = 23456;
  at.z_um = -100;
  const auto rest = resume_commands(cmds, at, EncodeOptions{});
  std::string letters;
  for (const auto& c : rest) letters += static_cast<char>(c.letter);
  ASSERT_GE(letters.size(), 6u);
  EXPECT_EQ(letters.substr(0, 6), "UZFZJB");
  proto::RapidMoveCmd f{};
  proto::decode(rest[2].payload.data(), static_cast<uint8_t>(rest[2].payload.size()), &f);
  EXPECT_EQ(f.x_um, 12345);
  EXPECT_EQ(f.y_um, 23456);
  proto::JobMarkCmd j{};
  proto::decode(rest[4].payload.data(), static_cast<uint8_t>(rest[4].payload.size()), &j);
  EXPECT_EQ(j.job_index, 4);
  EXPECT_EQ(j.first_point, 17);
  EXPECT_EQ(rest.size() - 5, cmds.size() - b);  // the rest of the job, unchanged
  // Past the end: nothing to do.
  at.job_index = 1000;
  EXPECT_TRUE(resume_commands(cmds, at, EncodeOptions{}).empty());
}

}  // namespace
}  // namespace host

namespace host {
namespace {

// The controller's curve point count stops at 65 535: on a longer curve that says only that
// the tool got that far, so resuming mid-curve is refused with what to do instead, never done
// at a wrapped, wrong point (a curve that long needs a pathological shape; the rule is tested
// on counts).
TEST(SendResume, ASaturatedCurvePointOnALongerCurveIsNotResumedMidCurve) {
  const std::string why = curve_point_problem(7, 70000, 0xFFFF);
  EXPECT_NE(why.find("counts only 65 535"), std::string::npos) << why;
  EXPECT_NE(why.find("--resume-at 7:0"), std::string::npos) << why;
  EXPECT_EQ(curve_point_problem(7, 70000, 65534), "");
  // 65 536 points: heading for 65 535 is heading for the last one, whatever comes after.
  EXPECT_EQ(curve_point_problem(7, 0x10000, 0xFFFF), "");
  EXPECT_NE(curve_point_problem(7, 0x10001, 0xFFFF), "");
  EXPECT_NE(curve_point_problem(7, 100, 100).find("has 100 points, not 101"), std::string::npos);
  EXPECT_NE(curve_point_problem(7, 1, 1).find("has 1 point, not 2"), std::string::npos);
  EXPECT_EQ(curve_point_problem(7, 100, 99), "");
}

}  // namespace
}  // namespace host
