// Which position a continued job starts from, and the stream from there.
#include "host/lib/server/job_continue.h"

#include <fmt/format.h>  // fmt::format

#include <optional>  // std::optional

#include "host/lib/stream/job_resume.h"

namespace host::server {

std::vector<QueuedCommand> continue_commands(const JobRecord& job,
                                             const std::vector<QueuedCommand>& full,
                                             const JobPlan& plan, const EncodeOptions& enc,
                                             Sender& sender, const ResumeEncoder& hook,
                                             const std::function<void(const std::string&)>& note) {
  // The new session stopped what was left: where the machine came to rest.
  const proto::StatusReply rest = sender.read_status_at_rest(std::chrono::seconds(30));
  const std::optional<ResumePoint> at = resume_point_of(rest);
  // The position saved while the job ran, if it is in this job's numbering (the same stream:
  // another machine's session limits can make another one).
  std::optional<ResumePoint> saved;
  if (job.resume_index >= 0 && job.resume_job_id == job_id_of(full) &&
      command_of_job_index(full, static_cast<int32_t>(job.resume_index)) < full.size()) {
    try {
      saved = resume_point_at(full, static_cast<int32_t>(job.resume_index),
                              static_cast<uint16_t>(job.resume_point), rest.z_um);
    } catch (const PlanError& e) {
      note(fmt::format("the saved position cannot be used: {}", e.what()));
    }
  }
  // The machine's own position counts when it is at or past the saved one (or the curve
  // continuing starts at): a job's older progress on this machine is not where it got to.
  size_t floor = full.size();
  if (saved) {
    floor = command_of_job_index(full, saved->job_index);
  } else {
    for (size_t i = 0; i < full.size() && floor == full.size(); ++i) {
      if (full[i].curve == job.start_curve) floor = i;
    }
  }
  if (at && resume_mismatch(full, *at).empty()) {
    const size_t mine = command_of_job_index(full, at->job_index);
    const bool ahead =
        mine > floor || (mine == floor && (!saved || at->curve_point >= job.resume_point));
    if (mine < full.size() && ahead) {
      note("continuing at " + describe_resume_point(full, *at) + ", where the machine stopped");
      return resume_commands(full, *at, enc);
    }
    if (mine >= full.size() && floor < full.size()) {
      note("the machine had finished the job: nothing left to send");
      return {};
    }
  }
  if (saved) {
    note("continuing at " + describe_resume_point(full, *saved) +
         ", the last position saved (this machine does not hold the job's progress: up to one "
         "save interval may be cut again)");
    return resume_commands(full, *saved, enc);
  }
  if (job.start_curve < 0) throw PlanError("no position to continue the job from");
  if (!hook) throw PlanError("continuing mid-job needs a resume encoder (WorkshopOptions)");
  note(fmt::format("continuing from curve {}", job.start_curve));
  return hook(plan, enc, job.start_curve);
}

}  // namespace host::server
