// What the SQL job stores (SQLite, PostgreSQL) share: the statements both run (written once,
// with the dialect's parameter mark '?' or '$'), the tag list format the fit queries match,
// and the clock they stamp. The jobs table's columns come from job_record_fields.h.
#ifndef HOST_LIB_SERVER_JOB_STORE_SQL_H
#define HOST_LIB_SERVER_JOB_STORE_SQL_H

#include <chrono>   // std::chrono::system_clock
#include <cstdint>  // int64_t
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/lib/server/job_record.h"  // MachineFit
#include "host/lib/server/job_record_fields.h"

namespace host::server::sql {

inline int64_t now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// ",pen,brass," so that a substring search finds ",pen," (tags hold no commas: the parser
// checks).
inline std::string tag_list(const MachineFit& fit) {
  std::string s = ",";
  for (const std::string& t : fit.tags) s += t + ",";
  return s;
}

// " AND id NOT IN (3,7)" for the jobs a machine leaves for now (MachineFit::not_now_ids;
// numbers only, never text from outside), "" for none.
inline std::string not_now_sql(const MachineFit& fit) {
  if (fit.not_now_ids.empty()) return "";
  std::string s = " AND id NOT IN (";
  for (size_t i = 0; i < fit.not_now_ids.size(); ++i)
    s += (i ? "," : "") + std::to_string(fit.not_now_ids[i]);
  return s + ")";
}

// The servers table's columns added after the first release: ALTERed into an older database at
// open (the jobs table's come from the field table: every column a database lacks).
struct AddedColumn {
  const char* table;
  const char* name;
  const char* type_and_default;
};
inline const AddedColumn kAddedServerColumns[] = {
    {"servers", "epoch", "BIGINT NOT NULL DEFAULT 0"},
    {"servers", "revoked", "INTEGER NOT NULL DEFAULT 0"},
    {"servers", "holder", "TEXT NOT NULL DEFAULT ''"},
};

// The running job's updates (progress, end) are fenced: only the server that claimed it, under
// the lease it claimed it with, while that lease stands. ?1/$1 id, then owner and epoch at the
// numbers given.
inline std::string fenced_running(char mark, int owner, int epoch) {
  const std::string o = mark + std::to_string(owner), e = mark + std::to_string(epoch);
  return "id = " + std::string(1, mark) + "1 AND state = 'running' AND owner = " + o +
         " AND lease_epoch = " + e + " AND EXISTS (SELECT 1 FROM servers WHERE name = " + o +
         " AND epoch = " + e + " AND revoked = 0)";
}

// Parameter n in the dialect's mark: "?3" (SQLite) or "$3" (PostgreSQL).
inline std::string param(char mark, int n) {
  return std::string(1, mark) + std::to_string(n);
}

// A running job's saved progress (JobProgress, in its order) from parameter `first` on:
// "executed = ?4, total = ?5, ...".
inline std::string progress_set(char mark, int first) {
  static const char* const kProgressColumns[] = {"executed",     "total",        "resume_curve",
                                                 "resume_index", "resume_point", "resume_job_id"};
  std::string out;
  for (const char* c : kProgressColumns) {
    out += std::string(out.empty() ? "" : ", ") + c + " = " + param(mark, first++);
  }
  return out;
}

// ?1 id, ?2 owner, ?3 epoch, ?4.. the progress.
inline std::string save_progress(char mark) {
  return "UPDATE jobs SET " + progress_set(mark, 4) + " WHERE " + fenced_running(mark, 2, 3);
}

// ?1 id, ?2 owner, ?3 epoch, ?4 state, ?5 message, ?6..?11 the progress, ?12 now.
inline std::string finish(char mark) {
  return "UPDATE jobs SET state = " + param(mark, 4) + ", message = " + param(mark, 5) + ", " +
         progress_set(mark, 6) + ", finished_ms = " + param(mark, 12) + " WHERE " +
         fenced_running(mark, 2, 3);
}

// ?1 id, ?2 now.
inline std::string cancel(char mark) {
  return "UPDATE jobs SET state = 'cancelled', finished_ms = " + param(mark, 2) +
         " WHERE id = " + param(mark, 1) + " AND state = 'queued'";
}

// ?1 id, ?2 now, ?3 message.
inline std::string fail_queued(char mark) {
  return "UPDATE jobs SET state = 'failed', message = " + param(mark, 3) +
         ", finished_ms = " + param(mark, 2) + " WHERE id = " + param(mark, 1) +
         " AND state = 'queued'";
}

// ?1 id. A queued job's message is cleared: the last run's verdict no longer applies
// (an outside tester saw a requeued job still saying why it had failed).
inline std::string requeue(char mark, bool continue_job) {
  return continue_job
             ? "UPDATE jobs SET state = 'queued', machine = '', owner = '', message = '',"
               " start_curve = resume_curve WHERE id = " +
                   param(mark, 1) +
                   " AND state = 'interrupted'"
                   " AND (resume_curve >= 0 OR resume_index >= 0 OR executed = 0)"
             : "UPDATE jobs SET state = 'queued', machine = '', owner = '', message = '',"
               " start_curve = -1,"
               " resume_curve = -1, resume_index = -1, resume_point = 0, resume_job_id = -1"
               " WHERE id = " +
                   param(mark, 1) + " AND state IN ('interrupted', 'aborted', 'failed')";
}

// ?1 id, ?2 priority.
inline std::string set_priority(char mark) {
  return "UPDATE jobs SET priority = " + param(mark, 2) + " WHERE id = " + param(mark, 1) +
         " AND state = 'queued'";
}

// ?1 owner, ?2 message, ?3 now.
inline std::string interrupt_running(char mark) {
  return "UPDATE jobs SET state = 'interrupted', message = " + param(mark, 2) +
         ", finished_ms = " + param(mark, 3) +
         " WHERE state = 'running' AND owner = " + param(mark, 1);
}

// ?1 message, ?2 now: running jobs not under a standing lease.
inline std::string interrupt_unleased(char mark) {
  return "UPDATE jobs SET state = 'interrupted', message = " + param(mark, 1) +
         ", finished_ms = " + param(mark, 2) +
         " WHERE state = 'running' AND NOT EXISTS (SELECT 1 FROM servers WHERE"
         " servers.name = jobs.owner AND servers.epoch = jobs.lease_epoch AND"
         " servers.revoked = 0)";
}

// ?1 owner, ?2 epoch.
inline std::string lease_stands(char mark) {
  return "SELECT 1 FROM servers WHERE name = " + param(mark, 1) + " AND epoch = " + param(mark, 2) +
         " AND revoked = 0";
}

// The claim's UPDATE after the chosen job: ?1 id (SQLite) or the job's sub-select; then
// machine, owner, now, epoch at the numbers given. Executed and total start at 0: a continued
// job is "planning" until this run's commands are made, not its last run's "cutting" (the
// resume position stays).
inline std::string claim_set(char mark, int machine) {
  return "UPDATE jobs SET state = 'running', machine = " + param(mark, machine) +
         ", owner = " + param(mark, machine + 1) + ", started_ms = " + param(mark, machine + 2) +
         ", message = '', executed = 0, total = 0, lease_epoch = " + param(mark, machine + 3);
}

// SELECT every column of one job (?1 id), or of the newest (?1 state or '', ?2 limit).
inline std::string select_job(char mark) {
  return "SELECT " + job_columns() + " FROM jobs WHERE id = " + param(mark, 1);
}
inline std::string select_jobs(char mark) {
  return "SELECT " + job_columns() + " FROM jobs WHERE (" + param(mark, 1) +
         " = '' OR state = " + param(mark, 1) + ") ORDER BY id DESC LIMIT " + param(mark, 2);
}

// The jobs table's columns that `present` lacks, declared for ALTER TABLE ADD COLUMN (an older
// database: every column a later version added, with its default).
template <class Present>
std::vector<std::string> missing_job_columns(SqlDialect dialect, Present present) {
  std::vector<std::string> out;
  for (size_t i = 0; i < kJobFieldCount; ++i) {
    if (!present(kJobFields[i].column)) out.push_back(column_declaration(kJobFields[i], dialect));
  }
  return out;
}

}  // namespace host::server::sql

#endif  // HOST_LIB_SERVER_JOB_STORE_SQL_H
