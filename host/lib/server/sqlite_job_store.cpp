// SQLite job store: one table, WAL journal, every change in one transaction.
#include "host/lib/server/sqlite_job_store.h"

#include <fmt/format.h>  // fmt::format
#include <sqlite3.h>     // sqlite3_*

#include "host/lib/server/job_store_sql.h"

namespace host::server {

namespace {

using sql::kColumns;
using sql::not_now_sql;
using sql::now_ms;
using sql::tag_list;

const char* kFitWhere =
    "state = 'queued' AND width_mm <= ?1 AND height_mm <= ?2 AND "
    "(tag = '' OR instr(?3, ',' || tag || ',') > 0)";

// A prepared statement that finalizes itself; errors name the database file.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& path, const std::string& sql) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) fail("prepare");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, int64_t v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  Statement& bind(int i, double v) {
    sqlite3_bind_double(stmt_, i, v);
    return *this;
  }
  Statement& bind(int i, const std::string& v) {
    sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  // True while a row is available.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail("step");
    return false;
  }
  int64_t i64(int c) const { return sqlite3_column_int64(stmt_, c); }
  double f64(int c) const { return sqlite3_column_double(stmt_, c); }
  std::string text(int c) const {
    const unsigned char* t = sqlite3_column_text(stmt_, c);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  JobRecord record() const {
    JobRecord r;
    r.id = i64(0);
    r.key = text(1);
    r.name = text(2);
    r.input_file = text(3);
    r.state = state_from_name(text(4));
    r.priority = static_cast<int>(i64(5));
    r.tag = text(6);
    r.settings.feed_mm_s = f64(7);
    r.settings.tol_mm = f64(8);
    r.settings.scale = f64(9);
    r.settings.margin_mm = f64(10);
    r.width_mm = f64(11);
    r.height_mm = f64(12);
    r.planned_s = f64(13);
    r.machine = text(14);
    r.owner = text(15);
    r.message = text(16);
    r.executed = i64(17);
    r.total = i64(18);
    r.resume_curve = static_cast<int>(i64(19));
    r.created_ms = i64(20);
    r.started_ms = i64(21);
    r.finished_ms = i64(22);
    r.start_curve = static_cast<int>(i64(23));
    r.resume_index = i64(24);
    r.resume_point = static_cast<int>(i64(25));
    r.resume_job_id = static_cast<int>(i64(26));
    r.lease_epoch = i64(27);
    return r;
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw StoreError(fmt::format("{}: {} failed: {}", path_, what, sqlite3_errmsg(db_)));
  }
  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

SqliteJobStore::SqliteJobStore(const std::string& path) : path_(path) {
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX;
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError(fmt::format("{}: cannot open the job database: {}", path, why));
  }
  sqlite3_busy_timeout(db_, 5000);
  exec("PRAGMA journal_mode = WAL");
  exec("PRAGMA synchronous = NORMAL");
  exec(
      "CREATE TABLE IF NOT EXISTS jobs ("
      " id INTEGER PRIMARY KEY AUTOINCREMENT, key TEXT NOT NULL UNIQUE, name TEXT NOT NULL,"
      " input_file TEXT NOT NULL, state TEXT NOT NULL, priority INTEGER NOT NULL,"
      " tag TEXT NOT NULL, feed_mm_s REAL NOT NULL, tol_mm REAL NOT NULL, scale REAL NOT NULL,"
      " margin_mm REAL NOT NULL, width_mm REAL NOT NULL, height_mm REAL NOT NULL,"
      " planned_s REAL NOT NULL, machine TEXT NOT NULL DEFAULT '',"
      " owner TEXT NOT NULL DEFAULT '', message TEXT NOT NULL DEFAULT '',"
      " executed INTEGER NOT NULL DEFAULT 0, total INTEGER NOT NULL DEFAULT 0,"
      " resume_curve INTEGER NOT NULL DEFAULT -1, created_ms INTEGER NOT NULL,"
      " started_ms INTEGER NOT NULL DEFAULT 0, finished_ms INTEGER NOT NULL DEFAULT 0,"
      " start_curve INTEGER NOT NULL DEFAULT -1)");
  exec("CREATE INDEX IF NOT EXISTS jobs_queue ON jobs (state, priority DESC, id)");
  exec("CREATE TABLE IF NOT EXISTS servers (name TEXT PRIMARY KEY, seen_ms INTEGER NOT NULL)");
  add_missing_columns();
}

void SqliteJobStore::add_missing_columns() {
  for (const sql::AddedColumn& c : sql::kAddedColumns) {
    bool present = false;
    {
      Statement s(db_, path_, fmt::format("PRAGMA table_info({})", c.table));
      while (s.step()) present = present || s.text(1) == c.name;
    }
    if (!present)
      exec(fmt::format("ALTER TABLE {} ADD COLUMN {} {}", c.table, c.name, c.type_and_default));
  }
}

SqliteJobStore::~SqliteJobStore() {
  sqlite3_close(db_);
}

void SqliteJobStore::exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string why = err ? err : "unknown error";
    sqlite3_free(err);
    throw StoreError(fmt::format("{}: {}", path_, why));
  }
}

int64_t SqliteJobStore::add(const JobRecord& job, const std::string& /*input: in the archive*/) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              "INSERT INTO jobs (key, name, input_file, state, priority, tag, feed_mm_s, tol_mm,"
              " scale, margin_mm, width_mm, height_mm, planned_s, created_ms)"
              " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14)");
  s.bind(1, job.key).bind(2, job.name).bind(3, job.input_file);
  s.bind(4, std::string(state_name(job.state))).bind(5, int64_t{job.priority}).bind(6, job.tag);
  s.bind(7, job.settings.feed_mm_s).bind(8, job.settings.tol_mm).bind(9, job.settings.scale);
  s.bind(10, job.settings.margin_mm).bind(11, job.width_mm).bind(12, job.height_mm);
  s.bind(13, job.planned_s).bind(14, now_ms());
  s.step();
  return sqlite3_last_insert_rowid(db_);
}

std::optional<JobRecord> SqliteJobStore::get(int64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_, fmt::format("SELECT {} FROM jobs WHERE id = ?1", kColumns));
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return s.record();
}

std::vector<JobRecord> SqliteJobStore::list(const std::string& state_filter, size_t limit) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              fmt::format("SELECT {} FROM jobs WHERE (?1 = '' OR state = ?1) ORDER BY id DESC "
                          "LIMIT ?2",
                          kColumns));
  s.bind(1, state_filter).bind(2, static_cast<int64_t>(limit));
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(s.record());
  return out;
}

bool SqliteJobStore::has_claimable(const MachineFit& fit) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              fmt::format("SELECT id FROM jobs WHERE {}{} LIMIT 1", kFitWhere, not_now_sql(fit)));
  s.bind(1, fit.work_width_mm).bind(2, fit.work_height_mm).bind(3, tag_list(fit));
  return s.step();
}

std::optional<JobRecord> SqliteJobStore::claim(const MachineFit& fit, const std::string& machine,
                                               const Lease& lease) {
  std::lock_guard<std::mutex> lock(mutex_);
  // IMMEDIATE: the write lock is taken before the SELECT, so another process using the same
  // file cannot claim the job (or revoke the lease) between our SELECT and UPDATE.
  exec("BEGIN IMMEDIATE");
  try {
    {
      Statement l(db_, path_,
                  "SELECT 1 FROM servers WHERE name = ?1 AND epoch = ?2 AND revoked = 0");
      l.bind(1, lease.owner).bind(2, lease.epoch);
      if (!l.step()) {
        exec("COMMIT");
        throw LeaseLost(fmt::format("{}: the lease of server '{}' (epoch {}) is gone", path_,
                                    lease.owner, lease.epoch));
      }
    }
    int64_t id = 0;
    {
      Statement s(db_, path_,
                  fmt::format("SELECT id FROM jobs WHERE {}{} ORDER BY priority DESC, id LIMIT 1",
                              kFitWhere, not_now_sql(fit)));
      s.bind(1, fit.work_width_mm).bind(2, fit.work_height_mm).bind(3, tag_list(fit));
      if (!s.step()) {
        exec("COMMIT");
        return std::nullopt;
      }
      id = s.i64(0);
    }
    Statement u(db_, path_,
                "UPDATE jobs SET state = 'running', machine = ?2, owner = ?3, started_ms = ?4,"
                " message = '', executed = 0, lease_epoch = ?5 WHERE id = ?1");
    u.bind(1, id).bind(2, machine).bind(3, lease.owner).bind(4, now_ms()).bind(5, lease.epoch);
    u.step();
    Statement r(db_, path_, fmt::format("SELECT {} FROM jobs WHERE id = ?1", kColumns));
    r.bind(1, id);
    r.step();
    JobRecord job = r.record();
    exec("COMMIT");
    return job;
  } catch (const LeaseLost&) {
    throw;
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

bool SqliteJobStore::save_progress(int64_t id, const Lease& lease, const JobProgress& p) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              "UPDATE jobs SET executed = ?4, total = ?5, resume_curve = ?6, resume_index = ?7,"
              " resume_point = ?8, resume_job_id = ?9 WHERE " +
                  sql::fenced_running('?', 2, 3));
  s.bind(1, id).bind(2, lease.owner).bind(3, lease.epoch).bind(4, p.executed).bind(5, p.total);
  s.bind(6, int64_t{p.resume_curve}).bind(7, p.resume_index).bind(8, int64_t{p.resume_point});
  s.bind(9, int64_t{p.resume_job_id});
  s.step();
  return sqlite3_changes(db_) == 1;
}

bool SqliteJobStore::finish(int64_t id, const Lease& lease, JobState state,
                            const std::string& message, const JobProgress& p) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              "UPDATE jobs SET state = ?4, message = ?5, executed = ?6, total = ?7,"
              " resume_curve = ?8, resume_index = ?9, resume_point = ?10, resume_job_id = ?11,"
              " finished_ms = ?12 WHERE " +
                  sql::fenced_running('?', 2, 3));
  s.bind(1, id).bind(2, lease.owner).bind(3, lease.epoch);
  s.bind(4, std::string(state_name(state))).bind(5, message).bind(6, p.executed);
  s.bind(7, p.total).bind(8, int64_t{p.resume_curve}).bind(9, p.resume_index);
  s.bind(10, int64_t{p.resume_point}).bind(11, int64_t{p.resume_job_id}).bind(12, now_ms());
  s.step();
  return sqlite3_changes(db_) == 1;
}

bool SqliteJobStore::cancel(int64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              "UPDATE jobs SET state = 'cancelled', finished_ms = ?2 WHERE id = ?1 AND state = "
              "'queued'");
  s.bind(1, id).bind(2, now_ms());
  s.step();
  return sqlite3_changes(db_) == 1;
}

bool SqliteJobStore::requeue(int64_t id, bool continue_job) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              continue_job
                  ? "UPDATE jobs SET state = 'queued', machine = '', owner = '',"
                    " start_curve = resume_curve WHERE id = ?1 AND state = 'interrupted'"
                    " AND (resume_curve >= 0 OR resume_index >= 0 OR executed = 0)"
                  : "UPDATE jobs SET state = 'queued', machine = '', owner = '', start_curve = -1,"
                    " resume_curve = -1, resume_index = -1, resume_point = 0,"
                    " resume_job_id = -1 WHERE id = ?1 AND state IN ('interrupted', 'aborted',"
                    " 'failed')");
  s.bind(1, id);
  s.step();
  return sqlite3_changes(db_) == 1;
}

bool SqliteJobStore::set_priority(int64_t id, int priority) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_, "UPDATE jobs SET priority = ?2 WHERE id = ?1 AND state = 'queued'");
  s.bind(1, id).bind(2, int64_t{priority});
  s.step();
  return sqlite3_changes(db_) == 1;
}

int SqliteJobStore::interrupt_running(const std::string& owner, const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              "UPDATE jobs SET state = 'interrupted', message = ?2, finished_ms = ?3"
              " WHERE state = 'running' AND owner = ?1");
  s.bind(1, owner).bind(2, message).bind(3, now_ms());
  s.step();
  return sqlite3_changes(db_);
}

Lease SqliteJobStore::acquire_lease(const std::string& owner, const std::string& holder,
                                    int64_t stale_ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  exec("BEGIN IMMEDIATE");
  try {
    const int64_t now = now_ms();
    {
      Statement s(db_, path_, "SELECT seen_ms, revoked, holder FROM servers WHERE name = ?1");
      s.bind(1, owner);
      if (s.step() && s.i64(1) == 0 && s.i64(0) >= now - stale_ms && s.text(2) != holder) {
        const std::string msg = fmt::format(
            "another server named '{}' is alive (last heard {:.1f} s ago, at {}): give this "
            "one its own --name, or wait {:.0f} s if that one has died",
            owner, (now - s.i64(0)) / 1000.0, s.text(2).empty() ? "?" : s.text(2),
            stale_ms / 1000.0);
        throw NameInUse(msg);
      }
    }
    Statement u(db_, path_,
                "INSERT INTO servers (name, seen_ms, epoch, revoked, holder)"
                " VALUES (?1, ?2, 1, 0, ?3) ON CONFLICT (name) DO UPDATE SET"
                " seen_ms = excluded.seen_ms, epoch = servers.epoch + 1, revoked = 0,"
                " holder = excluded.holder");
    u.bind(1, owner).bind(2, now).bind(3, holder);
    u.step();
    Statement e(db_, path_, "SELECT epoch FROM servers WHERE name = ?1");
    e.bind(1, owner);
    e.step();
    Lease lease{owner, e.i64(0)};
    exec("COMMIT");
    return lease;
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

bool SqliteJobStore::renew_lease(const Lease& lease) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_,
              "UPDATE servers SET seen_ms = ?3 WHERE name = ?1 AND epoch = ?2 AND revoked = 0");
  s.bind(1, lease.owner).bind(2, lease.epoch).bind(3, now_ms());
  s.step();
  return sqlite3_changes(db_) == 1;
}

int SqliteJobStore::interrupt_stale(int64_t stale_ms, const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  exec("BEGIN IMMEDIATE");
  try {
    const int64_t now = now_ms();
    {
      Statement r(db_, path_, "UPDATE servers SET revoked = 1 WHERE revoked = 0 AND seen_ms < ?1");
      r.bind(1, now - stale_ms);
      r.step();
    }
    Statement s(db_, path_,
                "UPDATE jobs SET state = 'interrupted', message = ?1, finished_ms = ?2"
                " WHERE state = 'running' AND NOT EXISTS (SELECT 1 FROM servers WHERE"
                " servers.name = jobs.owner AND servers.epoch = jobs.lease_epoch AND"
                " servers.revoked = 0)");
    s.bind(1, message).bind(2, now);
    s.step();
    const int n = sqlite3_changes(db_);
    exec("COMMIT");
    return n;
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

}  // namespace host::server
