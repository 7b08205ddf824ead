// The server's job record as one field table (as firmware/protocol/message_table.h is for the
// wire): the job's JSON, both stores' SQL (CREATE, INSERT, SELECT read by column name, the
// columns a migration adds), the upload's range checks and the docs check come from it.
// Defaults are not written here: a column's default is a default-constructed JobRecord's value
// (job_record.h, which takes them from host/lib/plan/job_defaults.h).
#ifndef HOST_LIB_SERVER_JOB_RECORD_FIELDS_H
#define HOST_LIB_SERVER_JOB_RECORD_FIELDS_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <cmath>    // NAN
#include <cstdint>  // int64_t
#include <string>   // std::string
#include <variant>  // std::variant

#include "host/lib/server/job_record.h"

namespace host::server {

enum class FieldType { kText, kInt, kInt64, kDouble, kState };

// How a column is declared beyond its type and default.
// kRowId: the primary key, numbered by the database.
enum class ColumnRole { kPlain, kRowId, kUnique };

// Where a field's value comes from.
enum class FieldSource { kUpload, kServer };

// X(type, member of JobRecord, JSON key ("" = not in the job's JSON), SQL column, role,
//   lowest, highest (an upload's range; NAN = not checked), who sets it: kUpload (an upload
//   field of the same name as the JSON key) or kServer)
// The JSON keys are the API's (docs/user-guide.md, "A job's fields"); width_mm and height_mm
// are given together as "size_mm" [w, h].
// clang-format off
#define ENGRAVER_JOB_RECORD_FIELDS(X) \
  X(kInt64,  id,                 "id",           "id",           kRowId,  NAN,   NAN,   kServer) \
  X(kText,   key,                "",             "key",          kUnique, NAN,   NAN,   kServer) \
  X(kText,   name,               "name",         "name",         kPlain,  NAN,   NAN,   kServer) \
  X(kText,   input_file,         "input_file",   "input_file",   kPlain,  NAN,   NAN,   kServer) \
  X(kState,  state,              "state",        "state",        kPlain,  NAN,   NAN,   kServer) \
  X(kInt,    priority,           "priority",     "priority",     kPlain,  -1000, 1000,  kUpload) \
  X(kText,   tag,                "tag",          "tag",          kPlain,  NAN,   NAN,   kUpload) \
  X(kDouble, settings.feed_mm_s, "feed_mm_s",    "feed_mm_s",    kPlain,  0.1,   60.0,  kUpload) \
  X(kDouble, settings.tol_mm,    "tol_mm",       "tol_mm",       kPlain,  0.001, 1.0,   kUpload) \
  X(kDouble, settings.scale,     "scale",        "scale",        kPlain,  1e-3,  1e3,   kUpload) \
  X(kDouble, settings.margin_mm, "margin_mm",    "margin_mm",    kPlain,  0.0,   100.0, kUpload) \
  X(kDouble, width_mm,           "",             "width_mm",     kPlain,  NAN,   NAN,   kServer) \
  X(kDouble, height_mm,          "",             "height_mm",    kPlain,  NAN,   NAN,   kServer) \
  X(kDouble, planned_s,          "planned_s",    "planned_s",    kPlain,  NAN,   NAN,   kServer) \
  X(kText,   machine,            "machine",      "machine",      kPlain,  NAN,   NAN,   kServer) \
  X(kText,   owner,              "server",       "owner",        kPlain,  NAN,   NAN,   kServer) \
  X(kText,   message,            "message",      "message",      kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  executed,           "executed",     "executed",     kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  total,              "total",        "total",        kPlain,  NAN,   NAN,   kServer) \
  X(kInt,    resume_curve,       "resume_curve", "resume_curve", kPlain,  NAN,   NAN,   kServer) \
  X(kInt,    start_curve,        "start_curve",  "start_curve",  kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  created_ms,         "created_ms",   "created_ms",   kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  started_ms,         "started_ms",   "started_ms",   kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  finished_ms,        "finished_ms",  "finished_ms",  kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  resume_index,       "",             "resume_index", kPlain,  NAN,   NAN,   kServer) \
  X(kInt,    resume_point,       "",             "resume_point", kPlain,  NAN,   NAN,   kServer) \
  X(kInt,    resume_job_id,      "",             "resume_job_id",kPlain,  NAN,   NAN,   kServer) \
  X(kInt64,  lease_epoch,        "",             "lease_epoch",  kPlain,  NAN,   NAN,   kServer)
// clang-format on

// One row of the table, with a pointer to its member in a given record.
struct JobField {
  FieldType type;
  const char* json_key;
  const char* column;
  ColumnRole role;
  double lowest;   // NAN: no range
  double highest;  // NAN: no range
  FieldSource source;
  void* (*member)(JobRecord&);
};
extern const JobField kJobFields[];
extern const size_t kJobFieldCount;

// The table row of a column, or null.
const JobField* job_field_by_column(const std::string& column);
// The table row of a JSON key, or null.
const JobField* job_field_by_json_key(const std::string& key);

// A field's value, as a store binds it (a state as its name).
using FieldValue = std::variant<std::string, int64_t, double>;
FieldValue field_value(const JobRecord& job, const JobField& field);
// The field's value in its default-constructed record.
FieldValue field_default(const JobField& field);
// Why `value` is out of the field's range ("" when in range or the field has none), in the
// words an upload gets ("feed_mm_s must be 0.1 .. 60"; written so that NaN fails).
std::string field_range_error(const JobField& field, double value);

// The job as the API gives it: every field with a JSON key, "size_mm" and the running job's
// "stage".
nlohmann::json job_record_json(const JobRecord& job);
// The JSON keys job_record_json writes, in its order (the docs check compares them).
std::vector<std::string> job_record_json_keys();

// ---- SQL, for both stores (`dialect` picks the column types) ----
enum class SqlDialect { kSqlite, kPostgres };
// "id, key, name, ..." in table order.
std::string job_columns();
// The column's declaration: "feed_mm_s REAL NOT NULL DEFAULT 10".
std::string column_declaration(const JobField& field, SqlDialect dialect);
// CREATE TABLE IF NOT EXISTS jobs (...), with `extra` appended to the column list
// (", input BYTEA NOT NULL" for a store that keeps the upload).
std::string create_jobs_table(SqlDialect dialect, const std::string& extra);
// "INSERT INTO jobs (key, ...) VALUES (M1, ...)" for every column but id, M the dialect's
// parameter mark ('?' or '$'); the values are insert_values(job) in that order, then the
// extra column's (a store's own: "input"), if any.
std::string insert_job(char mark, const std::string& extra_column = "");
std::vector<FieldValue> insert_values(const JobRecord& job);

// Builds a record from a result row read by column name. Row has text(column),
// i64(column) and f64(column).
template <class Row>
JobRecord job_from_row(const Row& row) {
  JobRecord job;
  for (size_t i = 0; i < kJobFieldCount; ++i) {
    const JobField& f = kJobFields[i];
    void* at = f.member(job);
    switch (f.type) {
      case FieldType::kText:
        *static_cast<std::string*>(at) = row.text(f.column);
        break;
      case FieldType::kState:
        *static_cast<JobState*>(at) = state_from_name(row.text(f.column));
        break;
      case FieldType::kInt:
        *static_cast<int*>(at) = static_cast<int>(row.i64(f.column));
        break;
      case FieldType::kInt64:
        *static_cast<int64_t*>(at) = row.i64(f.column);
        break;
      case FieldType::kDouble:
        *static_cast<double*>(at) = row.f64(f.column);
        break;
    }
  }
  return job;
}

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_RECORD_FIELDS_H
