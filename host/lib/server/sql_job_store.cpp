// The job store operations both SQL stores run alike (see sql_job_store.h).
#include "host/lib/server/sql_job_store.h"

#include <fmt/format.h>  // fmt::format

#include "host/lib/server/job_store_sql.h"

namespace host::server {

namespace {

// A running job's progress as parameters, in progress_set's order.
std::vector<FieldValue> progress_params(const JobProgress& p) {
  return {p.executed,
          p.total,
          int64_t{p.resume_curve},
          p.resume_index,
          int64_t{p.resume_point},
          int64_t{p.resume_job_id}};
}

}  // namespace

std::optional<JobRecord> SqlJobStore::get(int64_t id) {
  std::vector<JobRecord> r = query_jobs(sql::select_job(mark_), {id});
  if (r.empty()) return std::nullopt;
  return std::move(r[0]);
}

std::vector<JobRecord> SqlJobStore::list(const std::string& state_filter, size_t limit) {
  return query_jobs(sql::select_jobs(mark_), {state_filter, static_cast<int64_t>(limit)});
}

bool SqlJobStore::has_claimable(const MachineFit& fit) {
  return any_row(
      fmt::format("SELECT id FROM jobs WHERE {}{} LIMIT 1", fit_where_, sql::not_now_sql(fit)),
      {fit.work_width_mm, fit.work_height_mm, sql::tag_list(fit)});
}

bool SqlJobStore::save_progress(int64_t id, const Lease& lease, const JobProgress& p) {
  std::vector<FieldValue> params = {id, lease.owner, lease.epoch};
  for (FieldValue& v : progress_params(p)) params.push_back(std::move(v));
  return change(sql::save_progress(mark_), params) == 1;
}

bool SqlJobStore::finish(int64_t id, const Lease& lease, JobState state, const std::string& message,
                         const JobProgress& p) {
  std::vector<FieldValue> params = {id, lease.owner, lease.epoch, std::string(state_name(state)),
                                    message};
  for (FieldValue& v : progress_params(p)) params.push_back(std::move(v));
  params.push_back(sql::now_ms());
  return change(sql::finish(mark_), params) == 1;
}

bool SqlJobStore::cancel(int64_t id) {
  return change(sql::cancel(mark_), {id, sql::now_ms()}) == 1;
}

bool SqlJobStore::fail_queued(int64_t id, const std::string& message) {
  return change(sql::fail_queued(mark_), {id, sql::now_ms(), message}) == 1;
}

bool SqlJobStore::requeue(int64_t id, bool continue_job) {
  return change(sql::requeue(mark_, continue_job), {id}) == 1;
}

bool SqlJobStore::set_priority(int64_t id, int priority) {
  return change(sql::set_priority(mark_), {id, int64_t{priority}}) == 1;
}

int SqlJobStore::interrupt_running(const std::string& owner, const std::string& message) {
  return static_cast<int>(change(sql::interrupt_running(mark_), {owner, message, sql::now_ms()}));
}

}  // namespace host::server
