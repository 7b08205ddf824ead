// Job state names (one table, used by the store, the API and the page) and machine fit.
#include "host/lib/server/job_record.h"

#include <algorithm>  // std::find
#include <stdexcept>  // std::invalid_argument

namespace host::server {

namespace {

struct StateName {
  JobState state;
  const char* name;
};
const StateName kStateNames[] = {
    {JobState::kQueued, "queued"},       {JobState::kRunning, "running"},
    {JobState::kCompleted, "completed"}, {JobState::kAborted, "aborted"},
    {JobState::kFailed, "failed"},       {JobState::kInterrupted, "interrupted"},
    {JobState::kCancelled, "cancelled"}};

}  // namespace

const char* state_name(JobState state) {
  for (const StateName& s : kStateNames) {
    if (s.state == state) return s.name;
  }
  return "?";
}

JobState state_from_name(const std::string& name) {
  for (const StateName& s : kStateNames) {
    if (name == s.name) return s.state;
  }
  throw std::invalid_argument("unknown job state '" + name + "'");
}

bool is_final(JobState state) {
  return state == JobState::kCompleted || state == JobState::kAborted ||
         state == JobState::kFailed || state == JobState::kCancelled;
}

bool job_fits(const JobRecord& job, const MachineFit& fit) {
  if (job.width_mm > fit.work_width_mm || job.height_mm > fit.work_height_mm) return false;
  if (std::find(fit.not_now_ids.begin(), fit.not_now_ids.end(), job.id) != fit.not_now_ids.end())
    return false;
  return job.tag.empty() || std::find(fit.tags.begin(), fit.tags.end(), job.tag) != fit.tags.end();
}

}  // namespace host::server
