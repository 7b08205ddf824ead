// The job record's field table (job_record_fields.h) and everything made from it: JSON, SQL
// column declarations and statements, range checks.
#include "host/lib/server/job_record_fields.h"

#include <fmt/format.h>  // fmt::format

#include <cstring>  // std::strcmp

namespace host::server {

// clang-format off
#define ENGRAVER_JOB_FIELD_ROW(type, member_, json, column, role, lowest, highest, source)    \
  {FieldType::type, json, column, ColumnRole::role, lowest, highest, FieldSource::source,    \
   [](JobRecord& r) -> void* { return &r.member_; }},
// clang-format on
const JobField kJobFields[] = {ENGRAVER_JOB_RECORD_FIELDS(ENGRAVER_JOB_FIELD_ROW)};
#undef ENGRAVER_JOB_FIELD_ROW
const size_t kJobFieldCount = sizeof(kJobFields) / sizeof(kJobFields[0]);

const JobField* job_field_by_column(const std::string& column) {
  for (const JobField& f : kJobFields) {
    if (column == f.column) return &f;
  }
  return nullptr;
}

const JobField* job_field_by_json_key(const std::string& key) {
  for (const JobField& f : kJobFields) {
    if (*f.json_key != '\0' && key == f.json_key) return &f;
  }
  return nullptr;
}

FieldValue field_value(const JobRecord& job, const JobField& field) {
  // The table's accessor takes a record to write; reading through it changes nothing.
  void* at = field.member(const_cast<JobRecord&>(job));
  switch (field.type) {
    case FieldType::kText:
      return *static_cast<const std::string*>(at);
    case FieldType::kState:
      return std::string(state_name(*static_cast<const JobState*>(at)));
    case FieldType::kInt:
      return int64_t{*static_cast<const int*>(at)};
    case FieldType::kInt64:
      return *static_cast<const int64_t*>(at);
    case FieldType::kDouble:
      return *static_cast<const double*>(at);
  }
  return std::string();
}

FieldValue field_default(const JobField& field) {
  static const JobRecord kDefault;
  return field_value(kDefault, field);
}

std::string field_range_error(const JobField& field, double value) {
  if (std::isnan(field.lowest)) return "";
  if (value >= field.lowest && value <= field.highest) return "";
  const bool whole = field.type == FieldType::kInt || field.type == FieldType::kInt64;
  return fmt::format("{} must be {}{} .. {}", field.json_key, whole ? "an integer " : "",
                     field.lowest, field.highest);
}

nlohmann::json job_record_json(const JobRecord& job) {
  nlohmann::json j = nlohmann::json::object();
  for (const JobField& f : kJobFields) {
    if (*f.json_key == '\0') continue;
    std::visit([&](const auto& v) { j[f.json_key] = v; }, field_value(job, f));
  }
  j["size_mm"] = {job.width_mm, job.height_mm};
  // A running job before its commands are made has no size yet: not "0 of 0".
  j["stage"] = job.state != JobState::kRunning ? "" : job.total > 0 ? "cutting" : "planning";
  return j;
}

std::vector<std::string> job_record_json_keys() {
  std::vector<std::string> keys;
  for (const JobField& f : kJobFields) {
    if (*f.json_key != '\0') keys.push_back(f.json_key);
  }
  keys.push_back("size_mm");
  keys.push_back("stage");
  return keys;
}

std::string job_columns() {
  std::string out;
  for (const JobField& f : kJobFields) out += std::string(out.empty() ? "" : ", ") + f.column;
  return out;
}

namespace {

const char* sql_type(FieldType type, SqlDialect dialect) {
  const bool pg = dialect == SqlDialect::kPostgres;
  switch (type) {
    case FieldType::kText:
    case FieldType::kState:
      return "TEXT";
    case FieldType::kInt:
      return "INTEGER";
    case FieldType::kInt64:
      return pg ? "BIGINT" : "INTEGER";
    case FieldType::kDouble:
      return pg ? "DOUBLE PRECISION" : "REAL";
  }
  return "TEXT";
}

// The default as an SQL literal ('it''s' for text; the shortest exact form of a number).
std::string sql_literal(const FieldValue& v) {
  if (const std::string* s = std::get_if<std::string>(&v)) {
    std::string quoted = "'";
    for (char c : *s) quoted += c == '\'' ? std::string("''") : std::string(1, c);
    return quoted + "'";
  }
  if (const int64_t* i = std::get_if<int64_t>(&v)) return std::to_string(*i);
  return fmt::format("{}", std::get<double>(v));
}

}  // namespace

std::string column_declaration(const JobField& field, SqlDialect dialect) {
  if (field.role == ColumnRole::kRowId) {
    return fmt::format("{} {}", field.column,
                       dialect == SqlDialect::kPostgres ? "BIGSERIAL PRIMARY KEY"
                                                        : "INTEGER PRIMARY KEY AUTOINCREMENT");
  }
  return fmt::format("{} {} NOT NULL{} DEFAULT {}", field.column, sql_type(field.type, dialect),
                     field.role == ColumnRole::kUnique ? " UNIQUE" : "",
                     sql_literal(field_default(field)));
}

std::string create_jobs_table(SqlDialect dialect, const std::string& extra) {
  std::string columns;
  for (const JobField& f : kJobFields) {
    columns += std::string(columns.empty() ? "" : ", ") + column_declaration(f, dialect);
  }
  return fmt::format("CREATE TABLE IF NOT EXISTS jobs ({}{})", columns, extra);
}

std::string insert_job(char mark, const std::string& extra_column) {
  std::string columns, marks;
  int n = 0;
  for (const JobField& f : kJobFields) {
    if (f.role == ColumnRole::kRowId) continue;
    columns += std::string(n == 0 ? "" : ", ") + f.column;
    marks += fmt::format("{}{}{}", n == 0 ? "" : ", ", mark, n + 1);
    ++n;
  }
  if (!extra_column.empty()) {
    columns += ", " + extra_column;
    marks += fmt::format(", {}{}", mark, n + 1);
  }
  return fmt::format("INSERT INTO jobs ({}) VALUES ({})", columns, marks);
}

std::vector<FieldValue> insert_values(const JobRecord& job) {
  std::vector<FieldValue> values;
  for (const JobField& f : kJobFields) {
    if (f.role != ColumnRole::kRowId) values.push_back(field_value(job, f));
  }
  return values;
}

}  // namespace host::server
