// The job record's field table (job_record_fields.h): every field through the store and back,
// a database of the previous version opens with its jobs, and the user guide lists the
// fields of a job's JSON with the table's ranges.
#include <fmt/format.h>  // fmt::format
#include <gtest/gtest.h>
#include <sqlite3.h>  // sqlite3_exec: a database as the previous version left it

#include <algorithm>   // std::find
#include <cmath>       // std::isnan
#include <filesystem>  // std::filesystem::path
#include <fstream>     // std::ifstream
#include <set>         // std::set
#include <sstream>     // std::stringstream

#include "host/lib/server/http_api.h"  // upload_field_names
#include "host/lib/server/job_record_fields.h"
#include "host/lib/server/sqlite_job_store.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// Every member of JobRecord away from its default (written out here, not from the table: a
// field the table lacks is lost on the way and shows).
JobRecord every_field_set() {
  JobRecord j;
  j.key = "k1";
  j.name = "board's.dxf";
  j.input_file = "input.dxf";
  j.state = JobState::kInterrupted;
  j.priority = 7;
  j.tag = "pen";
  j.settings.feed_mm_s = 12.5;
  j.settings.tol_mm = 0.003;
  j.settings.scale = 2.25;
  j.settings.margin_mm = 3.75;
  j.width_mm = 101.5;
  j.height_mm = 55.25;
  j.planned_s = 321.5;
  j.machine = "m1";
  j.owner = "server1";
  j.message = "link lost";
  j.executed = 4000000000;  // beyond 32 bits
  j.total = 5000000000;
  j.resume_curve = 12;
  j.start_curve = 11;
  j.created_ms = 1700000000001;  // the store stamps its own
  j.started_ms = 1700000000002;
  j.finished_ms = 1700000000003;
  j.resume_index = 4000000001;
  j.resume_point = 9;
  j.resume_job_id = 33;
  j.lease_epoch = 6000000000;
  return j;
}

void expect_same_record(const JobRecord& a, const JobRecord& b) {
  EXPECT_EQ(a.key, b.key);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.input_file, b.input_file);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.priority, b.priority);
  EXPECT_EQ(a.tag, b.tag);
  EXPECT_EQ(a.settings.feed_mm_s, b.settings.feed_mm_s);
  EXPECT_EQ(a.settings.tol_mm, b.settings.tol_mm);
  EXPECT_EQ(a.settings.scale, b.settings.scale);
  EXPECT_EQ(a.settings.margin_mm, b.settings.margin_mm);
  EXPECT_EQ(a.width_mm, b.width_mm);
  EXPECT_EQ(a.height_mm, b.height_mm);
  EXPECT_EQ(a.planned_s, b.planned_s);
  EXPECT_EQ(a.machine, b.machine);
  EXPECT_EQ(a.owner, b.owner);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.executed, b.executed);
  EXPECT_EQ(a.total, b.total);
  EXPECT_EQ(a.resume_curve, b.resume_curve);
  EXPECT_EQ(a.start_curve, b.start_curve);
  EXPECT_EQ(a.started_ms, b.started_ms);
  EXPECT_EQ(a.finished_ms, b.finished_ms);
  EXPECT_EQ(a.resume_index, b.resume_index);
  EXPECT_EQ(a.resume_point, b.resume_point);
  EXPECT_EQ(a.resume_job_id, b.resume_job_id);
  EXPECT_EQ(a.lease_epoch, b.lease_epoch);
}

TEST(JobRecordFields, EveryFieldAJobIsAddedWithComesBackFromTheStore) {
  TempDir dir;
  SqliteJobStore store((dir.path() / "jobs.sqlite").string());
  const JobRecord sent = every_field_set();
  const int64_t id = store.add(sent, "");
  const std::optional<JobRecord> got = store.get(id);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->id, id);
  EXPECT_GT(got->created_ms, 0);
  expect_same_record(sent, *got);
  ASSERT_EQ(store.list("interrupted", 10).size(), 1u);
  expect_same_record(sent, store.list("interrupted", 10)[0]);
}

TEST(JobRecordFields, TheJobsJsonHasEveryKeyedFieldWithItsValue) {
  const nlohmann::json j = job_record_json(every_field_set());
  EXPECT_EQ(j["state"], "interrupted");
  EXPECT_EQ(j["stage"], "");
  EXPECT_EQ(j["server"], "server1");
  EXPECT_EQ(j["margin_mm"], 3.75);
  EXPECT_EQ(j["executed"], 4000000000);
  EXPECT_EQ(j["size_mm"], nlohmann::json({101.5, 55.25}));
  EXPECT_FALSE(j.contains("key"));  // the archive folder's name stays on the server
  EXPECT_FALSE(j.contains("lease_epoch"));
  std::set<std::string> keys;
  for (const auto& item : j.items()) keys.insert(item.key());
  const std::vector<std::string> listed = job_record_json_keys();
  EXPECT_EQ(keys, std::set<std::string>(listed.begin(), listed.end()));
}

// The jobs table as the version before the field table made it (its CREATE, then the columns
// it ALTERed in), with one job in it.
void write_previous_version_database(const fs::path& file) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  const char* schema =
      "CREATE TABLE jobs ("
      " id INTEGER PRIMARY KEY AUTOINCREMENT, key TEXT NOT NULL UNIQUE, name TEXT NOT NULL,"
      " input_file TEXT NOT NULL, state TEXT NOT NULL, priority INTEGER NOT NULL,"
      " tag TEXT NOT NULL, feed_mm_s REAL NOT NULL, tol_mm REAL NOT NULL, scale REAL NOT NULL,"
      " margin_mm REAL NOT NULL, width_mm REAL NOT NULL, height_mm REAL NOT NULL,"
      " planned_s REAL NOT NULL, machine TEXT NOT NULL DEFAULT '',"
      " owner TEXT NOT NULL DEFAULT '', message TEXT NOT NULL DEFAULT '',"
      " executed INTEGER NOT NULL DEFAULT 0, total INTEGER NOT NULL DEFAULT 0,"
      " resume_curve INTEGER NOT NULL DEFAULT -1, created_ms INTEGER NOT NULL,"
      " started_ms INTEGER NOT NULL DEFAULT 0, finished_ms INTEGER NOT NULL DEFAULT 0,"
      " start_curve INTEGER NOT NULL DEFAULT -1);"
      "CREATE INDEX jobs_queue ON jobs (state, priority DESC, id);"
      "CREATE TABLE servers (name TEXT PRIMARY KEY, seen_ms INTEGER NOT NULL);"
      "ALTER TABLE jobs ADD COLUMN resume_index BIGINT NOT NULL DEFAULT -1;"
      "ALTER TABLE jobs ADD COLUMN resume_point INTEGER NOT NULL DEFAULT 0;"
      "ALTER TABLE jobs ADD COLUMN resume_job_id INTEGER NOT NULL DEFAULT -1;"
      "ALTER TABLE jobs ADD COLUMN lease_epoch BIGINT NOT NULL DEFAULT 0;"
      "ALTER TABLE servers ADD COLUMN epoch BIGINT NOT NULL DEFAULT 0;"
      "ALTER TABLE servers ADD COLUMN revoked INTEGER NOT NULL DEFAULT 0;"
      "ALTER TABLE servers ADD COLUMN holder TEXT NOT NULL DEFAULT '';"
      "INSERT INTO jobs (key, name, input_file, state, priority, tag, feed_mm_s, tol_mm, scale,"
      " margin_mm, width_mm, height_mm, planned_s, machine, owner, message, executed, total,"
      " resume_curve, created_ms, started_ms, finished_ms, start_curve, resume_index,"
      " resume_point, resume_job_id, lease_epoch) VALUES ('old1', 'old.ngc', 'input.ngc',"
      " 'interrupted', 3, 'pen', 7.5, 0.02, 1.5, 2.5, 40.5, 30.25, 99.5, 'm2', 'server2',"
      " 'link lost', 120, 400, 5, 1600000000000, 1600000000100, 1600000000200, -1, 118, 4, 21,"
      " 3);"
      "INSERT INTO servers (name, seen_ms, epoch, revoked, holder) VALUES ('server2', 1, 3, 0,"
      " 'pc:/data');";
  char* err = nullptr;
  const int rc = sqlite3_exec(db, schema, nullptr, nullptr, &err);
  const std::string why = err ? err : "";
  sqlite3_free(err);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << why;
}

TEST(JobRecordFields, ADatabaseOfThePreviousVersionOpensWithItsJobs) {
  TempDir dir;
  const fs::path file = dir.path() / "jobs.sqlite";
  write_previous_version_database(file);
  SqliteJobStore store(file.string());
  const std::optional<JobRecord> old = store.get(1);
  ASSERT_TRUE(old);
  EXPECT_EQ(old->key, "old1");
  EXPECT_EQ(old->name, "old.ngc");
  EXPECT_EQ(old->state, JobState::kInterrupted);
  EXPECT_EQ(old->priority, 3);
  EXPECT_EQ(old->settings.feed_mm_s, 7.5);
  EXPECT_EQ(old->settings.margin_mm, 2.5);
  EXPECT_EQ(old->width_mm, 40.5);
  EXPECT_EQ(old->owner, "server2");
  EXPECT_EQ(old->executed, 120);
  EXPECT_EQ(old->total, 400);
  EXPECT_EQ(old->resume_curve, 5);
  EXPECT_EQ(old->created_ms, 1600000000000);
  EXPECT_EQ(old->start_curve, -1);
  EXPECT_EQ(old->resume_index, 118);
  EXPECT_EQ(old->resume_point, 4);
  EXPECT_EQ(old->resume_job_id, 21);
  EXPECT_EQ(old->lease_epoch, 3);
  // It goes on working: continued from its saved place, claimed, and new jobs join it.
  EXPECT_TRUE(store.requeue(1, true));
  EXPECT_EQ(store.get(1)->start_curve, 5);
  const JobRecord sent = every_field_set();
  const int64_t id = store.add(sent, "");
  EXPECT_EQ(id, 2);
  expect_same_record(sent, *store.get(id));
  const Lease lease = store.acquire_lease("server2", "pc:/data", 30000);
  EXPECT_EQ(lease.epoch, 4);
  MachineFit pen;
  pen.tags = {"pen"};
  const std::optional<JobRecord> claimed = store.claim(pen, "m9", lease);
  ASSERT_TRUE(claimed);
  EXPECT_EQ(claimed->id, 1);
}

TEST(JobRecordFields, AFirstReleaseDatabaseGetsTheColumnsAddedSince) {
  TempDir dir;
  const fs::path file = dir.path() / "jobs.sqlite";
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db,
                           "CREATE TABLE jobs (id INTEGER PRIMARY KEY AUTOINCREMENT, key TEXT NOT "
                           "NULL UNIQUE, name TEXT NOT NULL, input_file TEXT NOT NULL, state TEXT "
                           "NOT NULL, priority INTEGER NOT NULL, tag TEXT NOT NULL, created_ms "
                           "INTEGER NOT NULL);"
                           "INSERT INTO jobs (key, name, input_file, state, priority, tag, "
                           "created_ms) VALUES ('a', 'a.dxf', 'input.dxf', 'queued', 0, '', 5);",
                           nullptr, nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
  }
  SqliteJobStore store(file.string());
  const std::optional<JobRecord> old = store.get(1);
  ASSERT_TRUE(old);
  // The columns it lacked, at the record's defaults (job_defaults.h).
  const JobRecord fresh;
  EXPECT_EQ(old->settings.margin_mm, fresh.settings.margin_mm);
  EXPECT_EQ(old->settings.feed_mm_s, fresh.settings.feed_mm_s);
  EXPECT_EQ(old->resume_curve, -1);
  EXPECT_EQ(old->resume_index, -1);
  EXPECT_EQ(old->machine, "");
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The rows of the user guide's table of a job's fields: key cell -> the whole row.
std::vector<std::pair<std::string, std::string>> guide_job_fields() {
  const std::string guide = read_text(fs::path(ENGRAVER_SOURCE_DIR) / "docs" / "user-guide.md");
  const size_t start = guide.find("A job's fields (JSON:");
  const size_t table = guide.find("| key | what |", start);
  std::vector<std::pair<std::string, std::string>> rows;
  if (start == std::string::npos || table == std::string::npos) return rows;
  std::stringstream lines(guide.substr(table));
  std::string line;
  std::getline(lines, line);  // header
  std::getline(lines, line);  // |---|---|
  while (std::getline(lines, line) && line.rfind("| `", 0) == 0) {
    const std::string keys = line.substr(2, line.find(" |", 2) - 2);  // "`a`, `b`"
    size_t at = 0;
    while ((at = keys.find('`', at)) != std::string::npos) {
      const size_t end = keys.find('`', at + 1);
      rows.emplace_back(keys.substr(at + 1, end - at - 1), line);
      at = end + 1;
    }
  }
  return rows;
}

TEST(JobRecordFields, TheUserGuideListsEveryFieldOfAJobWithItsRange) {
  const auto rows = guide_job_fields();
  ASSERT_FALSE(rows.empty()) << "no table of a job's fields in docs/user-guide.md";
  std::set<std::string> documented;
  for (const auto& row : rows) documented.insert(row.first);
  // The keys of the real answers (GET /api/jobs/ID and each of GET /api/jobs), those the
  // server works out for each answer (`waiting`, `height_map`, `runs`) with the stored ones.
  TempDir dir;
  test::ServerRig server(dir.path(), {});
  const int64_t id = server.upload_ok("square.ngc", test::squares_gcode(1, 10));
  std::set<std::string> answered;
  for (const nlohmann::json& j : {server.job(id), server.jobs().at(0)})
    for (const auto& item : j.items()) answered.insert(item.key());
  EXPECT_EQ(documented, answered);
  const std::vector<std::string> keys = job_record_json_keys();
  for (const std::string& key : keys) EXPECT_EQ(answered.count(key), 1u) << key;
  for (size_t i = 0; i < kJobFieldCount; ++i) {
    const JobField& f = kJobFields[i];
    if (std::isnan(f.lowest) || *f.json_key == '\0') continue;
    const std::string range = fmt::format("{} .. {}", f.lowest, f.highest);
    for (const auto& row : rows) {
      if (row.first == f.json_key) {
        EXPECT_NE(row.second.find(range), std::string::npos) << f.json_key << ": " << range;
      }
    }
  }
}

TEST(JobRecordFields, TheUserGuidesUploadRowNamesEveryUploadField) {
  const std::string guide = read_text(fs::path(ENGRAVER_SOURCE_DIR) / "docs" / "user-guide.md");
  const size_t row = guide.find("| `POST /api/jobs` |");
  ASSERT_NE(row, std::string::npos);
  const std::string line = guide.substr(row, guide.find('\n', row) - row);
  for (const std::string& field : upload_field_names()) {
    EXPECT_NE(line.find("`" + field + "`"), std::string::npos) << field;
  }
}

// The page's form: every field an upload field; the record's fields with the table's ranges as
// their min and max and the record's defaults as their values.
TEST(JobRecordFields, ThePagesFormTakesUploadFieldsInTheTablesRanges) {
  const std::string page = read_text(fs::path(ENGRAVER_WEB_DIR) / "index.html");
  const std::vector<std::string> known = upload_field_names();
  const std::string form = page.substr(page.find("<form id=\"upload\""));
  size_t at = 0;
  int ranged = 0;
  while ((at = form.find(" name=\"", at)) != std::string::npos && at < form.find("</form>")) {
    at += 7;
    const std::string name = form.substr(at, form.find('"', at) - at);
    EXPECT_NE(std::find(known.begin(), known.end(), name), known.end()) << name;
    const std::string tag = form.substr(at, form.find('>', at) - at);
    const JobField* f = job_field_by_json_key(name);
    if (f == nullptr || std::isnan(f->lowest)) continue;
    ++ranged;
    EXPECT_NE(tag.find(fmt::format("min=\"{}\"", f->lowest)), std::string::npos) << tag;
    EXPECT_NE(tag.find(fmt::format("max=\"{}\"", f->highest)), std::string::npos) << tag;
    // Its initial value is the record's default (job_defaults.h), not a figure of its own.
    const std::string value =
        std::visit([](const auto& v) { return fmt::format("value=\"{}\"", v); }, field_default(*f));
    EXPECT_NE(tag.find(value), std::string::npos) << tag << " wants " << value;
  }
  EXPECT_EQ(ranged, 2);  // priority, feed_mm_s
}

}  // namespace
}  // namespace host::server
