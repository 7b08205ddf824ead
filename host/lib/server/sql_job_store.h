// What the SQLite and PostgreSQL job stores do alike: the job changes and reads that are one
// statement of job_store_sql.h with the same parameters in both. A store says how it runs a
// statement in its database; claims and leases (a transaction of several statements, each
// database's own locking) stay in the stores.
#ifndef HOST_LIB_SERVER_SQL_JOB_STORE_H
#define HOST_LIB_SERVER_SQL_JOB_STORE_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/server/job_record_fields.h"  // FieldValue
#include "host/lib/server/job_store.h"

namespace host::server {

class SqlJobStore : public JobStore {
 public:
  std::optional<JobRecord> get(int64_t id) override;
  std::vector<JobRecord> list(const std::string& state_filter, size_t limit) override;
  bool has_claimable(const MachineFit& fit) override;
  bool save_progress(int64_t id, const Lease& lease, const JobProgress& progress) override;
  bool finish(int64_t id, const Lease& lease, JobState state, const std::string& message,
              const JobProgress& progress) override;
  bool cancel(int64_t id) override;
  bool fail_queued(int64_t id, const std::string& message) override;
  bool requeue(int64_t id, bool continue_job) override;
  bool set_priority(int64_t id, int priority) override;
  int interrupt_running(const std::string& owner, const std::string& message) override;

 protected:
  // mark: the dialect's parameter mark ('?' SQLite, '$' PostgreSQL); fit_where: the WHERE
  // condition of a queued job that fits a machine (parameters 1 width, 2 height, 3 tags).
  SqlJobStore(char mark, const char* fit_where) : mark_(mark), fit_where_(fit_where) {}
  char mark() const { return mark_; }
  const char* fit_where() const { return fit_where_; }

  // Each runs one statement (parameters numbered from 1, in order) in its own transaction,
  // under the store's lock; database errors become StoreError.
  // The rows the statement changed.
  virtual int64_t change(const std::string& statement, const std::vector<FieldValue>& params) = 0;
  // The jobs it selects (every column of job_columns()).
  virtual std::vector<JobRecord> query_jobs(const std::string& statement,
                                            const std::vector<FieldValue>& params) = 0;
  // Whether it selects any row.
  virtual bool any_row(const std::string& statement, const std::vector<FieldValue>& params) = 0;

 private:
  char mark_;
  const char* fit_where_;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_SQL_JOB_STORE_H
