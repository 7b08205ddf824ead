// SQLite job store: one table, WAL journal, every change in one transaction.
#include "host/lib/server/sqlite_job_store.h"

#include <fmt/format.h>  // fmt::format
#include <sqlite3.h>     // sqlite3_*

#include <cstring>  // std::strcmp

#include "host/lib/server/job_store_sql.h"

namespace host::server {

namespace {

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
  Statement& bind(int i, const FieldValue& v) {
    std::visit([&](const auto& x) { bind(i, x); }, v);
    return *this;
  }
  // Parameters ?1, ?2, ... in order.
  void bind_all(const std::vector<FieldValue>& params) {
    int i = 1;
    for (const FieldValue& v : params) bind(i++, v);
  }
  // The row's columns by name (a database's column order is its history's, not the table's).
  int column(const char* name) const {
    for (int c = 0, n = sqlite3_column_count(stmt_); c < n; ++c) {
      if (std::strcmp(sqlite3_column_name(stmt_, c), name) == 0) return c;
    }
    throw StoreError(fmt::format("{}: no column '{}' in the result", path_, name));
  }
  int64_t i64(const char* name) const { return i64(column(name)); }
  double f64(const char* name) const { return f64(column(name)); }
  std::string text(const char* name) const { return text(column(name)); }
  JobRecord record() const { return job_from_row(*this); }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw StoreError(fmt::format("{}: {} failed: {}", path_, what, sqlite3_errmsg(db_)));
  }
  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

SqliteJobStore::SqliteJobStore(const std::string& path) : SqlJobStore('?', kFitWhere), path_(path) {
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
  exec(create_jobs_table(SqlDialect::kSqlite, ""));
  exec("CREATE INDEX IF NOT EXISTS jobs_queue ON jobs (state, priority DESC, id)");
  exec("CREATE TABLE IF NOT EXISTS servers (name TEXT PRIMARY KEY, seen_ms INTEGER NOT NULL)");
  add_missing_columns();
}

bool SqliteJobStore::has_column(const char* table, const char* column) {
  Statement s(db_, path_, fmt::format("PRAGMA table_info({})", table));
  bool present = false;
  while (s.step()) present = present || s.text(1) == column;
  return present;
}

void SqliteJobStore::add_missing_columns() {
  for (const std::string& c : sql::missing_job_columns(
           SqlDialect::kSqlite, [this](const char* column) { return has_column("jobs", column); }))
    exec("ALTER TABLE jobs ADD COLUMN " + c);
  for (const sql::AddedColumn& c : sql::kAddedServerColumns) {
    if (!has_column(c.table, c.name))
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

int64_t SqliteJobStore::change(const std::string& statement,
                               const std::vector<FieldValue>& params) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_, statement);
  s.bind_all(params);
  s.step();
  return sqlite3_changes(db_);
}

std::vector<JobRecord> SqliteJobStore::query_jobs(const std::string& statement,
                                                  const std::vector<FieldValue>& params) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_, statement);
  s.bind_all(params);
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(s.record());
  return out;
}

bool SqliteJobStore::any_row(const std::string& statement, const std::vector<FieldValue>& params) {
  std::lock_guard<std::mutex> lock(mutex_);
  Statement s(db_, path_, statement);
  s.bind_all(params);
  return s.step();
}

int64_t SqliteJobStore::add(const JobRecord& job, const std::string& /*input: in the archive*/) {
  std::lock_guard<std::mutex> lock(mutex_);
  JobRecord stamped = job;
  stamped.created_ms = now_ms();
  Statement s(db_, path_, insert_job('?'));
  s.bind_all(insert_values(stamped));
  s.step();
  return sqlite3_last_insert_rowid(db_);
}

std::optional<JobRecord> SqliteJobStore::claim(const MachineFit& fit, const std::string& machine,
                                               const Lease& lease) {
  std::lock_guard<std::mutex> lock(mutex_);
  // IMMEDIATE: the write lock is taken before the SELECT, so another process using the same
  // file cannot claim the job (or revoke the lease) between our SELECT and UPDATE.
  exec("BEGIN IMMEDIATE");
  try {
    {
      Statement l(db_, path_, sql::lease_stands('?'));
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
    Statement u(db_, path_, sql::claim_set('?', 2) + " WHERE id = ?1");
    u.bind(1, id).bind(2, machine).bind(3, lease.owner).bind(4, now_ms()).bind(5, lease.epoch);
    u.step();
    Statement r(db_, path_, sql::select_job('?'));
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
    Statement s(db_, path_, sql::interrupt_unleased('?'));
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
