// What the SQL job stores (SQLite, PostgreSQL) share: the jobs table's column list in the
// order both read rows, the tag list format the fit queries match, and the clock they stamp.
#ifndef HOST_LIB_SERVER_JOB_STORE_SQL_H
#define HOST_LIB_SERVER_JOB_STORE_SQL_H

#include <chrono>   // std::chrono::system_clock
#include <cstdint>  // int64_t
#include <string>   // std::string

#include "host/lib/server/job_record.h"  // MachineFit

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

inline const char* const kColumns =
    "id, key, name, input_file, state, priority, tag, feed_mm_s, tol_mm, scale, margin_mm, "
    "width_mm, height_mm, planned_s, machine, owner, message, executed, total, resume_curve, "
    "created_ms, started_ms, finished_ms, start_curve, resume_index, resume_point, "
    "resume_job_id, lease_epoch";

// Columns added after the first release: ALTERed into an older database at open.
struct AddedColumn {
  const char* table;
  const char* name;
  const char* type_and_default;
};
inline const AddedColumn kAddedColumns[] = {
    {"jobs", "resume_index", "BIGINT NOT NULL DEFAULT -1"},
    {"jobs", "resume_point", "INTEGER NOT NULL DEFAULT 0"},
    {"jobs", "resume_job_id", "INTEGER NOT NULL DEFAULT -1"},
    {"jobs", "lease_epoch", "BIGINT NOT NULL DEFAULT 0"},
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

}  // namespace host::server::sql

#endif  // HOST_LIB_SERVER_JOB_STORE_SQL_H
