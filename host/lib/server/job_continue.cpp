// Which position a continued job starts from, and the stream from there.
#include "host/lib/server/job_continue.h"

#include <fmt/format.h>  // fmt::format

#include <cstdint>   // SIZE_MAX
#include <optional>  // std::optional

#include "host/lib/stream/job_resume.h"

namespace host::server {

namespace {

// Stream index of the first command of plan curve `curve` (the job's size: none).
size_t first_command_of_curve(const JobPass& pass, int curve) {
  size_t index = 0, found = SIZE_MAX;
  pass([&](const QueuedCommand& c) {
    if (found == SIZE_MAX && c.curve == curve) found = index;
    ++index;
  });
  return found == SIZE_MAX ? index : found;
}

// The job from resume point `at` on: its prefix, then the plan's commands from there.
void resume_from(const JobPass& pass, const ResumePoint& at, const EncodeOptions& enc,
                 JobStream* stream) {
  size_t from = 0;
  std::vector<QueuedCommand> prefix = resume_prefix(pass, at, enc, &from);
  if (prefix.empty())
    stream->use_list({});
  else
    stream->start_at(from, std::move(prefix));
}

}  // namespace

std::vector<QueuedCommand> ContinueFromCurve::operator()(const JobPlan& plan,
                                                         const EncodeOptions& options,
                                                         int first_curve) const {
  return resume_from_curve(encode_job(plan, options), first_curve, options);
}

void continue_stream(const JobRecord& job, const JobPlan& plan, const EncodeOptions& enc,
                     Sender& sender, const ResumeEncoder& hook, bool machine_ran_it,
                     const std::function<void(const std::string&)>& note, JobStream* stream) {
  // The whole job encoded again for each look (nothing of it is held).
  const JobPass pass = pass_over(plan, enc, stream->job_id());
  const size_t total = stream->whole_job_size();
  // The new session stopped what was left: where the machine came to rest.
  const proto::StatusReply rest = sender.read_status_at_rest(std::chrono::seconds(30));
  const std::optional<ResumePoint> at = resume_point_of(rest);
  // The position saved while the job ran, if it is in this job's numbering (the same stream:
  // another machine's session limits can make another one).
  std::optional<ResumePoint> saved;
  if (job.resume_index >= 0 && job.resume_job_id == stream->job_id() &&
      ResumeScan(pass, static_cast<int32_t>(job.resume_index)).found()) {
    try {
      saved = resume_point_at(pass, static_cast<int32_t>(job.resume_index),
                              static_cast<uint16_t>(job.resume_point), rest.z_um);
    } catch (const PlanError& e) {
      note(fmt::format("the saved position cannot be used: {}", e.what()));
    }
  }
  // The machine's own position counts when it is at or past the saved one (or the curve
  // continuing starts at): a job's older progress on this machine is not where it got to.
  const size_t floor = saved ? ResumeScan(pass, saved->job_index).from()
                             : first_command_of_curve(pass, job.start_curve);
  if (at && !machine_ran_it && resume_mismatch(stream->job_id(), *at).empty())
    note("the machine's position is not used: it last ran another job (or none recorded)");
  if (at && machine_ran_it && resume_mismatch(stream->job_id(), *at).empty()) {
    const size_t mine = ResumeScan(pass, at->job_index).from();
    const bool ahead =
        mine > floor || (mine == floor && (!saved || at->curve_point >= job.resume_point));
    if (mine < total && ahead) {
      note("continuing at " + describe_resume_point(pass, *at) + ", where the machine stopped");
      resume_from(pass, *at, enc, stream);
      return;
    }
    if (mine >= total && floor < total) {
      note("the machine had finished the job: nothing left to send");
      stream->use_list({});
      return;
    }
  }
  if (saved) {
    note("continuing at " + describe_resume_point(pass, *saved) +
         ", the last position saved (this machine does not hold the job's progress: up to one "
         "save interval may be cut again)");
    resume_from(pass, *saved, enc, stream);
    return;
  }
  if (job.start_curve < 0) throw PlanError("no position to continue the job from");
  if (!hook) throw PlanError("continuing mid-job needs a resume encoder (WorkshopOptions)");
  note(fmt::format("continuing from curve {}", job.start_curve));
  if (hook.target<ContinueFromCurve>() != nullptr) {  // the default: streamed
    resume_from(pass, resume_point_at(pass, job_index_of_curve(pass, job.start_curve), 0, 0), enc,
                stream);
    return;
  }
  stream->use_list(hook(plan, enc, job.start_curve));
}

}  // namespace host::server
