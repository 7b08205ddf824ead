// PostgreSQL job store (libpqxx): the same table and rules as the SQLite store.
#include "host/lib/server/postgres_job_store.h"

#include <fmt/format.h>  // fmt::format

#include <pqxx/pqxx>  // pqxx::connection, pqxx::work

#include "host/lib/server/job_store_sql.h"

namespace host::server {

struct PostgresJobStore::Connection {
  explicit Connection(const std::string& conninfo) : db(conninfo) {}
  pqxx::connection db;
};

namespace {

using sql::kColumns;
using sql::not_now_sql;
using sql::now_ms;
using sql::tag_list;

// Lease times come from the database's clock: servers on several PCs need not agree on theirs.
const char* kDbNowMs = "(extract(epoch from clock_timestamp()) * 1000)::bigint";

const char* kFitWhere =
    "state = 'queued' AND width_mm <= $1 AND height_mm <= $2 AND "
    "(tag = '' OR position(',' || tag || ',' in $3) > 0)";

JobRecord record(const pqxx::row& row) {
  JobRecord r;
  r.id = row[0].as<int64_t>();
  r.key = row[1].as<std::string>();
  r.name = row[2].as<std::string>();
  r.input_file = row[3].as<std::string>();
  r.state = state_from_name(row[4].as<std::string>());
  r.priority = row[5].as<int>();
  r.tag = row[6].as<std::string>();
  r.settings.feed_mm_s = row[7].as<double>();
  r.settings.tol_mm = row[8].as<double>();
  r.settings.scale = row[9].as<double>();
  r.settings.margin_mm = row[10].as<double>();
  r.width_mm = row[11].as<double>();
  r.height_mm = row[12].as<double>();
  r.planned_s = row[13].as<double>();
  r.machine = row[14].as<std::string>();
  r.owner = row[15].as<std::string>();
  r.message = row[16].as<std::string>();
  r.executed = row[17].as<int64_t>();
  r.total = row[18].as<int64_t>();
  r.resume_curve = row[19].as<int>();
  r.created_ms = row[20].as<int64_t>();
  r.started_ms = row[21].as<int64_t>();
  r.finished_ms = row[22].as<int64_t>();
  r.start_curve = row[23].as<int>();
  r.resume_index = row[24].as<int64_t>();
  r.resume_point = row[25].as<int>();
  r.resume_job_id = row[26].as<int>();
  r.lease_epoch = row[27].as<int64_t>();
  return r;
}

}  // namespace

// Runs `body` in one transaction; database errors become StoreError.
#define PG_TRY(body)                                                     \
  try {                                                                  \
    body                                                                 \
  } catch (const pqxx::failure& e) {                                     \
    throw StoreError(fmt::format("PostgreSQL job store: {}", e.what())); \
  }

PostgresJobStore::PostgresJobStore(const std::string& conninfo){PG_TRY({
  conn_ = std::make_unique<Connection>(conninfo);
  pqxx::work w(conn_->db);
  // Two servers starting at once: the advisory lock makes the CREATEs take turns.
  w.exec("SELECT pg_advisory_xact_lock(4711)");
  w.exec(
      "CREATE TABLE IF NOT EXISTS jobs ("
      " id BIGSERIAL PRIMARY KEY, key TEXT NOT NULL UNIQUE, name TEXT NOT NULL,"
      " input_file TEXT NOT NULL, state TEXT NOT NULL, priority INTEGER NOT NULL,"
      " tag TEXT NOT NULL, feed_mm_s DOUBLE PRECISION NOT NULL,"
      " tol_mm DOUBLE PRECISION NOT NULL, scale DOUBLE PRECISION NOT NULL,"
      " margin_mm DOUBLE PRECISION NOT NULL, width_mm DOUBLE PRECISION NOT NULL,"
      " height_mm DOUBLE PRECISION NOT NULL, planned_s DOUBLE PRECISION NOT NULL,"
      " machine TEXT NOT NULL DEFAULT '', owner TEXT NOT NULL DEFAULT '',"
      " message TEXT NOT NULL DEFAULT '', executed BIGINT NOT NULL DEFAULT 0,"
      " total BIGINT NOT NULL DEFAULT 0, resume_curve INTEGER NOT NULL DEFAULT -1,"
      " created_ms BIGINT NOT NULL, started_ms BIGINT NOT NULL DEFAULT 0,"
      " finished_ms BIGINT NOT NULL DEFAULT 0, start_curve INTEGER NOT NULL DEFAULT -1,"
      " input BYTEA NOT NULL)");
  w.exec("CREATE INDEX IF NOT EXISTS jobs_queue ON jobs (state, priority DESC, id)");
  w.exec("CREATE TABLE IF NOT EXISTS servers (name TEXT PRIMARY KEY, seen_ms BIGINT NOT NULL)");
  for (const sql::AddedColumn& c : sql::kAddedColumns) {
    w.exec(fmt::format("ALTER TABLE {} ADD COLUMN IF NOT EXISTS {} {}", c.table, c.name,
                       c.type_and_default));
  }
  w.commit();
})}

PostgresJobStore::~PostgresJobStore() = default;

int64_t PostgresJobStore::add(const JobRecord& job, const std::string& input) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::binarystring bytes(input);
    const pqxx::row r = w.exec_params1(
        "INSERT INTO jobs (key, name, input_file, state, priority, tag, feed_mm_s, tol_mm,"
        " scale, margin_mm, width_mm, height_mm, planned_s, created_ms, input)"
        " VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15)"
        " RETURNING id",
        job.key, job.name, job.input_file, std::string(state_name(job.state)), job.priority,
        job.tag, job.settings.feed_mm_s, job.settings.tol_mm, job.settings.scale,
        job.settings.margin_mm, job.width_mm, job.height_mm, job.planned_s, now_ms(), bytes);
    w.commit();
    return r[0].as<int64_t>();
  })
}

std::optional<std::string> PostgresJobStore::input(int64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params("SELECT input FROM jobs WHERE id = $1", id);
    if (r.empty()) return std::nullopt;
    return pqxx::binarystring(r[0][0]).str();
  })
}

std::optional<JobRecord> PostgresJobStore::get(int64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r =
        w.exec_params(fmt::format("SELECT {} FROM jobs WHERE id = $1", kColumns), id);
    if (r.empty()) return std::nullopt;
    return record(r[0]);
  })
}

std::vector<JobRecord> PostgresJobStore::list(const std::string& state_filter, size_t limit) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        fmt::format("SELECT {} FROM jobs WHERE ($1 = '' OR state = $1) ORDER BY id DESC LIMIT $2",
                    kColumns),
        state_filter, static_cast<int64_t>(limit));
    std::vector<JobRecord> out;
    for (const pqxx::row& row : r) out.push_back(record(row));
    return out;
  })
}

bool PostgresJobStore::has_claimable(const MachineFit& fit) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    return !w.exec_params(
                 fmt::format("SELECT id FROM jobs WHERE {}{} LIMIT 1", kFitWhere, not_now_sql(fit)),
                 fit.work_width_mm, fit.work_height_mm, tag_list(fit))
                .empty();
  })
}

std::optional<JobRecord> PostgresJobStore::claim(const MachineFit& fit, const std::string& machine,
                                                 const Lease& lease) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    // FOR SHARE: a revocation (interrupt_stale) waits for this claim, then interrupts it.
    if (w.exec_params("SELECT 1 FROM servers WHERE name = $1 AND epoch = $2 AND revoked = 0"
                      " FOR SHARE",
                      lease.owner, lease.epoch)
            .empty()) {
      throw LeaseLost(
          fmt::format("PostgreSQL job store: the lease of server '{}' (epoch {}) "
                      "is gone",
                      lease.owner, lease.epoch));
    }
    // The row is locked by the inner SELECT; another server's claim skips it instead of
    // waiting, then finds the next job.
    const pqxx::result r = w.exec_params(
        fmt::format("UPDATE jobs SET state = 'running', machine = $4, owner = $5,"
                    " started_ms = $6, message = '', executed = 0, lease_epoch = $7"
                    " WHERE id = (SELECT id FROM jobs WHERE {}{} ORDER BY priority DESC, id"
                    " LIMIT 1 FOR UPDATE SKIP LOCKED) RETURNING {}",
                    kFitWhere, not_now_sql(fit), kColumns),
        fit.work_width_mm, fit.work_height_mm, tag_list(fit), machine, lease.owner, now_ms(),
        lease.epoch);
    w.commit();
    if (r.empty()) return std::nullopt;
    return record(r[0]);
  })
}

bool PostgresJobStore::save_progress(int64_t id, const Lease& lease, const JobProgress& p) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        "UPDATE jobs SET executed = $4, total = $5, resume_curve = $6, resume_index = $7,"
        " resume_point = $8, resume_job_id = $9 WHERE " +
            sql::fenced_running('$', 2, 3),
        id, lease.owner, lease.epoch, p.executed, p.total, p.resume_curve, p.resume_index,
        p.resume_point, p.resume_job_id);
    w.commit();
    return r.affected_rows() == 1;
  })
}

bool PostgresJobStore::finish(int64_t id, const Lease& lease, JobState state,
                              const std::string& message, const JobProgress& p) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        "UPDATE jobs SET state = $4, message = $5, executed = $6, total = $7,"
        " resume_curve = $8, resume_index = $9, resume_point = $10, resume_job_id = $11,"
        " finished_ms = $12 WHERE " +
            sql::fenced_running('$', 2, 3),
        id, lease.owner, lease.epoch, std::string(state_name(state)), message, p.executed, p.total,
        p.resume_curve, p.resume_index, p.resume_point, p.resume_job_id, now_ms());
    w.commit();
    return r.affected_rows() == 1;
  })
}

bool PostgresJobStore::cancel(int64_t id) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        "UPDATE jobs SET state = 'cancelled', finished_ms = $2 WHERE id = $1 AND state = "
        "'queued'",
        id, now_ms());
    w.commit();
    return r.affected_rows() == 1;
  })
}

bool PostgresJobStore::requeue(int64_t id, bool continue_job) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        continue_job
            ? "UPDATE jobs SET state = 'queued', machine = '', owner = '',"
              " start_curve = resume_curve WHERE id = $1 AND state = 'interrupted'"
              " AND (resume_curve >= 0 OR resume_index >= 0 OR executed = 0)"
            : "UPDATE jobs SET state = 'queued', machine = '', owner = '', start_curve = -1,"
              " resume_curve = -1, resume_index = -1, resume_point = 0, resume_job_id = -1"
              " WHERE id = $1 AND state IN ('interrupted', 'aborted', 'failed')",
        id);
    w.commit();
    return r.affected_rows() == 1;
  })
}

bool PostgresJobStore::set_priority(int64_t id, int priority) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        "UPDATE jobs SET priority = $2 WHERE id = $1 AND state = 'queued'", id, priority);
    w.commit();
    return r.affected_rows() == 1;
  })
}

int PostgresJobStore::interrupt_running(const std::string& owner, const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r = w.exec_params(
        "UPDATE jobs SET state = 'interrupted', message = $2, finished_ms = $3"
        " WHERE state = 'running' AND owner = $1",
        owner, message, now_ms());
    w.commit();
    return static_cast<int>(r.affected_rows());
  })
}

Lease PostgresJobStore::acquire_lease(const std::string& owner, const std::string& holder,
                                      int64_t stale_ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    w.exec_params(
        "INSERT INTO servers (name, seen_ms, epoch, revoked, holder) VALUES ($1, 0, 0, 1, '')"
        " ON CONFLICT (name) DO NOTHING",
        owner);
    const pqxx::row row = w.exec_params1(
        fmt::format("SELECT seen_ms, revoked, holder, {} FROM servers WHERE name = $1 FOR UPDATE",
                    kDbNowMs),
        owner);
    const int64_t seen = row[0].as<int64_t>();
    const int64_t now = row[3].as<int64_t>();
    const std::string held_by = row[2].as<std::string>();
    if (row[1].as<int>() == 0 && seen >= now - stale_ms && held_by != holder) {
      throw NameInUse(fmt::format(
          "another server named '{}' is alive (last heard {:.1f} s ago, at {}): give this one "
          "its own --name, or wait {:.0f} s if that one has died",
          owner, (now - seen) / 1000.0, held_by.empty() ? "?" : held_by, stale_ms / 1000.0));
    }
    const pqxx::row e = w.exec_params1(
        fmt::format("UPDATE servers SET seen_ms = {}, epoch = epoch + 1, revoked = 0,"
                    " holder = $2 WHERE name = $1 RETURNING epoch",
                    kDbNowMs),
        owner, holder);
    w.commit();
    Lease lease;
    lease.owner = owner;
    lease.epoch = e[0].as<int64_t>();
    return lease;
  })
}

bool PostgresJobStore::renew_lease(const Lease& lease) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    const pqxx::result r =
        w.exec_params(fmt::format("UPDATE servers SET seen_ms = {} WHERE name = $1 AND epoch = $2"
                                  " AND revoked = 0",
                                  kDbNowMs),
                      lease.owner, lease.epoch);
    w.commit();
    return r.affected_rows() == 1;
  })
}

int PostgresJobStore::interrupt_stale(int64_t stale_ms, const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  PG_TRY({
    pqxx::work w(conn_->db);
    w.exec_params(
        fmt::format("UPDATE servers SET revoked = 1 WHERE revoked = 0 AND seen_ms < {} - $1",
                    kDbNowMs),
        stale_ms);
    const pqxx::result r = w.exec_params(
        "UPDATE jobs SET state = 'interrupted', message = $1, finished_ms = $2"
        " WHERE state = 'running' AND NOT EXISTS (SELECT 1 FROM servers WHERE"
        " servers.name = jobs.owner AND servers.epoch = jobs.lease_epoch AND"
        " servers.revoked = 0)",
        message, now_ms());
    w.commit();
    return static_cast<int>(r.affected_rows());
  })
}

}  // namespace host::server
