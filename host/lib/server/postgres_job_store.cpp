// PostgreSQL job store (libpqxx): the same table and rules as the SQLite store.
#include "host/lib/server/postgres_job_store.h"

#include <fmt/format.h>  // fmt::format

#include <libpq-fe.h>  // PQconninfoParse
#include <pqxx/pqxx>   // pqxx::connection, pqxx::work

#include "host/lib/server/job_store_sql.h"

namespace host::server {

namespace {

// libpq's messages end with a newline; ours are one line.
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

}  // namespace

std::string postgres_conninfo_problem(const std::string& conninfo) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(conninfo.c_str(), &error);
  std::string problem;
  if (options == nullptr) problem = one_line(error != nullptr ? error : "libpq is out of memory");
  PQconninfoFree(options);
  PQfreemem(error);
  return problem;
}

struct PostgresJobStore::Connection {
  explicit Connection(const std::string& conninfo) : db(conninfo) {}
  pqxx::connection db;
};

namespace {

using sql::not_now_sql;
using sql::now_ms;
using sql::tag_list;

// Lease times come from the database's clock: servers on several PCs need not agree on theirs.
const char* kDbNowMs = "(extract(epoch from clock_timestamp()) * 1000)::bigint";

const char* kFitWhere =
    "state = 'queued' AND width_mm <= $1 AND height_mm <= $2 AND "
    "(tag = '' OR position(',' || tag || ',' in $3) > 0)";

// A result row read by column name (job_from_row).
struct NamedRow {
  const pqxx::row& row;
  std::string text(const char* column) const { return row[column].as<std::string>(); }
  int64_t i64(const char* column) const { return row[column].as<int64_t>(); }
  double f64(const char* column) const { return row[column].as<double>(); }
};

JobRecord record(const pqxx::row& row) {
  return job_from_row(NamedRow{row});
}

// A field's value as a statement parameter (the column's type converts it; a number in its
// shortest exact form).
std::string param_text(const FieldValue& v) {
  if (const std::string* s = std::get_if<std::string>(&v)) return *s;
  if (const int64_t* i = std::get_if<int64_t>(&v)) return std::to_string(*i);
  return fmt::format("{}", std::get<double>(v));
}

// A database error as the store's error.
StoreError store_error(const pqxx::failure& e) {
  return StoreError(fmt::format("PostgreSQL job store: {}", one_line(e.what())));
}

// Runs body(work) under the store's lock in one transaction (which the body commits);
// database errors become StoreError.
template <class Body>
auto transact(std::mutex& mutex, pqxx::connection& db, Body body) {
  std::lock_guard<std::mutex> lock(mutex);
  try {
    pqxx::work w(db);
    return body(w);
  } catch (const pqxx::failure& e) {
    throw store_error(e);
  }
}

// A statement with its parameters as text (as libpqxx sends any type; the columns' types
// convert them).
pqxx::result exec_with(pqxx::work& w, const std::string& statement,
                       const std::vector<FieldValue>& params) {
  std::vector<std::string> texts;
  for (const FieldValue& v : params) texts.push_back(param_text(v));
  return w.exec_params(statement, pqxx::prepare::make_dynamic_params(texts));
}

}  // namespace

PostgresJobStore::PostgresJobStore(const std::string& conninfo) : SqlJobStore('$', kFitWhere) {
  try {
    conn_ = std::make_unique<Connection>(conninfo);
  } catch (const pqxx::failure& e) {
    throw store_error(e);
  }
  transact(mutex_, conn_->db, [](pqxx::work& w) {
    // Two servers starting at once: the advisory lock makes the CREATEs take turns.
    w.exec("SELECT pg_advisory_xact_lock(4711)");
    w.exec(create_jobs_table(SqlDialect::kPostgres, ", input BYTEA NOT NULL"));
    w.exec("CREATE INDEX IF NOT EXISTS jobs_queue ON jobs (state, priority DESC, id)");
    w.exec("CREATE TABLE IF NOT EXISTS servers (name TEXT PRIMARY KEY, seen_ms BIGINT NOT NULL)");
    const auto present = [&w](const char* column) {
      return !w.exec_params(
                   "SELECT 1 FROM information_schema.columns WHERE table_name = 'jobs'"
                   " AND column_name = $1 AND table_schema = current_schema()",
                   std::string(column))
                  .empty();
    };
    for (const std::string& c : sql::missing_job_columns(SqlDialect::kPostgres, present))
      w.exec("ALTER TABLE jobs ADD COLUMN " + c);
    for (const sql::AddedColumn& c : sql::kAddedServerColumns) {
      w.exec(fmt::format("ALTER TABLE {} ADD COLUMN IF NOT EXISTS {} {}", c.table, c.name,
                         c.type_and_default));
    }
    w.commit();
  });
}

PostgresJobStore::~PostgresJobStore() = default;

int64_t PostgresJobStore::change(const std::string& statement,
                                 const std::vector<FieldValue>& params) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) {
    const pqxx::result r = exec_with(w, statement, params);
    w.commit();
    return static_cast<int64_t>(r.affected_rows());
  });
}

std::vector<JobRecord> PostgresJobStore::query_jobs(const std::string& statement,
                                                    const std::vector<FieldValue>& params) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) {
    const pqxx::result r = exec_with(w, statement, params);
    std::vector<JobRecord> out;
    for (const pqxx::row& row : r) out.push_back(record(row));
    return out;
  });
}

bool PostgresJobStore::any_row(const std::string& statement,
                               const std::vector<FieldValue>& params) {
  return transact(mutex_, conn_->db,
                  [&](pqxx::work& w) { return !exec_with(w, statement, params).empty(); });
}

int64_t PostgresJobStore::add(const JobRecord& job, const std::string& input) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) {
    const pqxx::binarystring bytes(input);
    JobRecord stamped = job;
    stamped.created_ms = now_ms();
    std::vector<std::string> values;
    for (const FieldValue& v : insert_values(stamped)) values.push_back(param_text(v));
    const pqxx::row r = w.exec_params1(insert_job('$', "input") + " RETURNING id",
                                       pqxx::prepare::make_dynamic_params(values), bytes);
    w.commit();
    return r[0].as<int64_t>();
  });
}

std::optional<std::string> PostgresJobStore::input(int64_t id) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) -> std::optional<std::string> {
    const pqxx::result r = w.exec_params("SELECT input FROM jobs WHERE id = $1", id);
    if (r.empty()) return std::nullopt;
    return pqxx::binarystring(r[0][0]).str();
  });
}

std::optional<JobRecord> PostgresJobStore::claim(const MachineFit& fit, const std::string& machine,
                                                 const Lease& lease) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) -> std::optional<JobRecord> {
    // FOR SHARE: a revocation (interrupt_stale) waits for this claim, then interrupts it.
    if (w.exec_params(sql::lease_stands('$') + " FOR SHARE", lease.owner, lease.epoch).empty()) {
      throw LeaseLost(
          fmt::format("PostgreSQL job store: the lease of server '{}' (epoch {}) "
                      "is gone",
                      lease.owner, lease.epoch));
    }
    // The row is locked by the inner SELECT; another server's claim skips it instead of
    // waiting, then finds the next job.
    const pqxx::result r = w.exec_params(
        fmt::format("{} WHERE id = (SELECT id FROM jobs WHERE {}{} ORDER BY priority DESC, id"
                    " LIMIT 1 FOR UPDATE SKIP LOCKED) RETURNING {}",
                    sql::claim_set('$', 4), kFitWhere, not_now_sql(fit), job_columns()),
        fit.work_width_mm, fit.work_height_mm, tag_list(fit), machine, lease.owner, now_ms(),
        lease.epoch);
    w.commit();
    if (r.empty()) return std::nullopt;
    return record(r[0]);
  });
}

Lease PostgresJobStore::acquire_lease(const std::string& owner, const std::string& holder,
                                      int64_t stale_ms) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) {
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
  });
}

bool PostgresJobStore::renew_lease(const Lease& lease) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) {
    const pqxx::result r =
        w.exec_params(fmt::format("UPDATE servers SET seen_ms = {} WHERE name = $1 AND epoch = $2"
                                  " AND revoked = 0",
                                  kDbNowMs),
                      lease.owner, lease.epoch);
    w.commit();
    return r.affected_rows() == 1;
  });
}

int PostgresJobStore::interrupt_stale(int64_t stale_ms, const std::string& message) {
  return transact(mutex_, conn_->db, [&](pqxx::work& w) {
    w.exec_params(
        fmt::format("UPDATE servers SET revoked = 1 WHERE revoked = 0 AND seen_ms < {} - $1",
                    kDbNowMs),
        stale_ms);
    const pqxx::result r = w.exec_params(sql::interrupt_unleased('$'), message, now_ms());
    w.commit();
    return static_cast<int>(r.affected_rows());
  });
}

}  // namespace host::server
