// The job store in PostgreSQL: several servers (one per room or PC) share one queue. A job
// is claimed with SELECT ... FOR UPDATE SKIP LOCKED inside one UPDATE, so two servers never
// take the same job; the uploaded file is kept in the database so any server can run it.
#ifndef HOST_LIB_SERVER_POSTGRES_JOB_STORE_H
#define HOST_LIB_SERVER_POSTGRES_JOB_STORE_H

#include <memory>  // std::unique_ptr
#include <mutex>   // std::mutex
#include <string>  // std::string

#include "host/lib/server/sql_job_store.h"

namespace host::server {

// What libpq finds wrong with a connection string without connecting (an option it does not
// know, "=x", a malformed URI), "" when it reads.
std::string postgres_conninfo_problem(const std::string& conninfo);

class PostgresJobStore : public SqlJobStore {
 public:
  // conninfo: libpq's "host=... dbname=..." or a postgresql:// URI. Creates the table if
  // needed. Throws StoreError (the password, if any, is not repeated).
  explicit PostgresJobStore(const std::string& conninfo);
  ~PostgresJobStore() override;

  int64_t add(const JobRecord& job, const std::string& input) override;
  std::optional<std::string> input(int64_t id) override;
  std::optional<JobRecord> claim(const MachineFit& fit, const std::string& machine,
                                 const Lease& lease) override;
  Lease acquire_lease(const std::string& owner, const std::string& holder,
                      int64_t stale_ms) override;
  bool renew_lease(const Lease& lease) override;
  int interrupt_stale(int64_t stale_ms, const std::string& message) override;

 private:
  int64_t change(const std::string& statement, const std::vector<FieldValue>& params) override;
  std::vector<JobRecord> query_jobs(const std::string& statement,
                                    const std::vector<FieldValue>& params) override;
  bool any_row(const std::string& statement, const std::vector<FieldValue>& params) override;
  struct Connection;  // pqxx::connection (a typedef in libpqxx 6: not forward-declarable)
  std::unique_ptr<Connection> conn_;
  std::mutex mutex_;  // a libpq connection serves one thread at a time
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_POSTGRES_JOB_STORE_H
