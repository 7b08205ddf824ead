// `engraver send` as a function (see send_command.h).
#include "host/lib/commands/send_command.h"

#include <stdint.h>  // INT32_MAX

#include <fmt/format.h>  // fmt::format

#include <stdexcept>  // std::invalid_argument
#include <vector>     // std::vector

#include "host/lib/commands/exit_codes.h"
#include "host/lib/heightmap/controller_map.h"  // job_map_commands
#include "host/lib/plan/counted.h"              // counted: "1 hole", "2 holes"
#include "host/lib/stream/command_source.h"     // EncodedJob
#include "host/lib/stream/job_resume.h"
#include "host/lib/stream/resume_scan.h"  // ResumeScan: the job's job commands counted

namespace host::commands {

int exit_code_of(JobOutcome outcome) {
  switch (outcome) {
    case JobOutcome::kCompleted:
      return kExitOk;
    case JobOutcome::kAborted:
      return kExitAborted;
    case JobOutcome::kAlarm:
      return kExitAlarm;
    case JobOutcome::kRejected:
      return kExitRefused;
    case JobOutcome::kLinkLost:
      return kExitLinkLost;
    case JobOutcome::kStalled:
      return kExitStalled;
  }
  return kExitJobFailed;
}

ResumeAt parse_resume_at(const std::string& text) {
  const size_t colon = text.find(':');
  // Digits only ("+3", " 3" and 3 with a blank after alike refused), within the wire's
  // fields: a job command index is 31 bits (99999999999 wrapped to 1215752191).
  auto whole = [](const std::string& digits, long long max) {
    if (digits.empty() || digits.size() > 12 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      throw std::invalid_argument(digits);
    const long long v = std::stoll(digits);
    if (v > max) throw std::out_of_range(digits);
    return v;
  };
  try {
    const long long index = whole(text.substr(0, colon), INT32_MAX);
    const long long point = colon == std::string::npos ? 0 : whole(text.substr(colon + 1), 65535);
    return ResumeAt{static_cast<int32_t>(index), static_cast<uint16_t>(point), text};
  } catch (const std::exception&) {
    throw CommandFailure(kExitUsage,
                         fmt::format("--resume-at: '{}': expected INDEX or INDEX:POINT (job "
                                     "command and curve point as the progress line shows them: "
                                     "whole numbers, INDEX at most 2147483647, POINT at most "
                                     "65535)",
                                     text));
  }
}

void check_resume_at(const JobPlan& plan, const EncodeOptions& encode, const ResumeAt& at) {
  // One pass. The session may change how curves are framed, never what the job commands
  // are; the #J's job_id is not needed to count them.
  const ResumeScan scan(pass_over(plan, encode, 0), at.index);
  if (!scan.found()) {
    // The count a finished job's progress line ends with ("job 72:0") is one past the last.
    throw CommandFailure(
        kExitUsage,
        fmt::format("--resume-at: '{}': this job has {} (INDEX 0 .. {}) of its {}; "
                    "a progress line's 'job {}' means the job had finished",
                    at.text, counted(scan.job_commands(), "job command"), scan.job_commands() - 1,
                    counted(scan.commands(), "command"), scan.job_commands()));
  }
  if (at.point > 0 && scan.at().front().letter != proto::kCmdSplineHeader) {
    throw CommandFailure(kExitUsage,
                         fmt::format("--resume-at: '{}': job command {} is not a curve (a move, a "
                                     "pause or a setting): it has no point {}, only 0",
                                     at.text, at.index, at.point));
  }
  try {
    resume_point_at(scan, at.point, 0);
  } catch (const PlanError& e) {
    throw CommandFailure(kExitUsage, fmt::format("--resume-at: '{}': {}", at.text, e.what()));
  }
}

void refuse_unzeroed_machine(Sender& sender, const std::string& command) {
  if (sender.read_status().flags & proto::kStatusZeroed) return;
  throw CommandFailure(
      kExitJobFailed,
      fmt::format("the machine is not zeroed and --no-zero does not start manual zeroing: "
                  "nothing was sent (without --no-zero, {} starts it: jog to the corner with "
                  "the joystick and press confirm)",
                  command));
}

namespace {

// Where the controller's stopped job goes on: the resume point from its status or the
// --resume-at figures, checked against this job (the plan encoded again: no list is held).
ResumePoint resume_point(const SendOptions& o, Sender& sender, const JobPass& job,
                         uint16_t job_id) {
  // The new session stopped what was left: where it came to rest is where to go on.
  const proto::StatusReply status = sender.read_status_at_rest(std::chrono::seconds(30));
  if (o.resume_at) return resume_point_at(job, o.resume_at->index, o.resume_at->point, status.z_um);
  const std::optional<ResumePoint> at = resume_point_of(status);
  if (!at) {
    throw CommandFailure(
        kExitJobFailed,
        "the controller reports no job progress (it was restarted or never ran a job): zero it "
        "at the job's zero point again and use --resume-at INDEX:POINT with the 'job' figures "
        "of the last progress line");
  }
  const std::string mismatch = resume_mismatch(job_id, *at);
  if (!mismatch.empty()) throw CommandFailure(kExitJobFailed, mismatch);
  return *at;
}

// The setup frames that go before what is left of the job (a resume's prefix), the job's
// stream set to start where it goes on and the bytes of the job's commands it leaves out;
// false when nothing is left.
bool resume_stream(const SendOptions& o, Sender& sender, const JobPlan& plan,
                   const EncodeOptions& enc, EncodedJob* job, std::vector<QueuedCommand>* setup,
                   size_t* skipped_bytes, std::ostream& log) {
  const JobPass pass = pass_over(plan, enc, job->summary().job_id);
  const ResumePoint at = resume_point(o, sender, pass, job->summary().job_id);
  log << fmt::format("engraver: resuming at {}; the tool goes to ({:.3f}, {:.3f}) mm\n",
                     describe_resume_point(pass, at), at.x_um / 1000.0, at.y_um / 1000.0);
  size_t from = 0;
  *setup = resume_prefix(pass, at, enc, &from);
  if (setup->empty()) return false;
  job->start_at(from);
  size_t index = 0;
  pass([&](const QueuedCommand& c) {
    if (index++ < from) *skipped_bytes += frame_bytes(c);
  });
  return true;
}

// Streams the commands with the operator's controls attached; the outcome.
JobOutcome stream(Sender& sender, CommandSource& commands, const SendOptions& o,
                  std::ostream& log) {
  std::shared_ptr<void> keys = o.while_streaming ? o.while_streaming(sender) : nullptr;
  bool told_zero = false;
  return sender.run(commands, [&](const Progress& p) {
    if (p.status.state == proto::MachineState::kZeroing && !told_zero) {
      log << "engraver: zero the machine: jog to the corner with the joystick, then press "
             "confirm\n";
      told_zero = true;
    }
    if (o.on_progress) o.on_progress(p);
  });
}

// Detaches the operator's controls from the sender however the job ends.
struct ControlsAttached {
  ControlsAttached(const SendOptions& o, Sender* sender) : o_(o) {
    if (o_.attach_controls) o_.attach_controls(sender);
  }
  ~ControlsAttached() {
    if (o_.attach_controls) o_.attach_controls(nullptr);
  }
  const SendOptions& o_;
};

}  // namespace

SendResult send_job(Link& link, const JobPlan& plan, const SendOptions& o, std::ostream& log) {
  Sender sender(link, o.sender);
  sender.set_note([&log](const std::string& line) { log << "engraver: " << line << "\n"; });
  const ControlsAttached controls(o, &sender);
  const proto::SessionReply caps = sender.open_session();
  if (!o.sender.zero_first) refuse_unzeroed_machine(sender, "send");  // before probe or resume
  EncodeOptions enc = o.encode;
  use_session(caps, &enc);
  enc.controller = &caps;
  // Encoded as the sender goes: memory does not grow with the job.
  EncodedJob commands(plan, enc);
  SendResult r;
  r.job_id = commands.summary().job_id;
  std::vector<QueuedCommand> setup;
  size_t skipped_bytes = 0;
  if ((o.resume || o.resume_at) &&
      !resume_stream(o, sender, plan, enc, &commands, &setup, &skipped_bytes, log)) {
    log << "engraver: nothing to resume: the controller says the job has finished\n";
    r.nothing_left = true;
    return r;
  }
  std::optional<heightmap::HeightMap> map = o.map;
  if (o.probe) {
    log << "engraver: probing the blank: the probe clip on the blank, the spindle off\n";
    map = o.probe(sender);
  }
  // The map goes first (a controller that restarted has lost it: a resume sends it again);
  // without one, a clear: no map of an earlier job compensates this one.
  std::vector<QueuedCommand> frames = heightmap::job_map_commands(map ? &*map : nullptr);
  frames.insert(frames.end(), setup.begin(), setup.end());
  const size_t bytes = wire_bytes(frames) + commands.summary().wire_bytes - skipped_bytes;
  const size_t setup_n = frames.size();
  commands.set_setup(std::move(frames));
  // Counted as run's report counts them: the job's commands, and the set-up before them
  // (the progress line counts both).
  log << fmt::format(
      "engraver: {} -> {}: {}, {} (and {} before the job: the height map or its "
      "clearing{}), {} bytes of frames for both (status queries and resends come on top), job id "
      "{}; keys: h hold, r resume, x abort, +/- feed override\n",
      o.file, link.name(), counted(plan.curves.size(), "curve"),
      counted(commands.size() - setup_n, "command"), counted(setup_n, "set-up command"),
      setup.empty() ? "" : ", and what the resume restores", bytes, r.job_id);
  r.commands = commands.size();
  r.outcome = stream(sender, commands, o, log);
  r.message = sender.message();
  r.commands_held_max = commands.held_max();
  r.stats = sender.stats();
  if (r.outcome == JobOutcome::kCompleted) log << "engraver: " << send_ending_text(r) << "\n";
  return r;
}

std::string send_ending_text(const SendResult& r) {
  return fmt::format("job {}: {} ({}, {} bytes, {} resent after busy or loss)",
                     outcome_name(r.outcome), r.message, counted(r.stats.frames_sent, "frame"),
                     r.stats.bytes_sent, r.stats.retransmits);
}

}  // namespace host::commands
