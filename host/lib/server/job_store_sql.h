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

inline const char* const kColumns =
    "id, key, name, input_file, state, priority, tag, feed_mm_s, tol_mm, scale, margin_mm, "
    "width_mm, height_mm, planned_s, machine, owner, message, executed, total, resume_curve, "
    "created_ms, started_ms, finished_ms, start_curve";

}  // namespace host::server::sql

#endif  // HOST_LIB_SERVER_JOB_STORE_SQL_H
