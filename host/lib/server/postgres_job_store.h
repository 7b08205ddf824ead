// The job store in PostgreSQL: several servers (one per room or PC) share one queue. A job
// is claimed with SELECT ... FOR UPDATE SKIP LOCKED inside one UPDATE, so two servers never
// take the same job; the uploaded file is kept in the database so any server can run it.
#ifndef HOST_LIB_SERVER_POSTGRES_JOB_STORE_H
#define HOST_LIB_SERVER_POSTGRES_JOB_STORE_H

#include <memory>  // std::unique_ptr
#include <mutex>   // std::mutex
#include <string>  // std::string

#include "host/lib/server/job_store.h"

namespace host::server {

class PostgresJobStore : public JobStore {
 public:
  // conninfo: libpq's "host=... dbname=..." or a postgresql:// URI. Creates the table if
  // needed. Throws StoreError (the password, if any, is not repeated).
  explicit PostgresJobStore(const std::string& conninfo);
  ~PostgresJobStore() override;

  int64_t add(const JobRecord& job, const std::string& input) override;
  std::optional<std::string> input(int64_t id) override;
  std::optional<JobRecord> get(int64_t id) override;
  std::vector<JobRecord> list(const std::string& state_filter, size_t limit) override;
  bool has_claimable(const MachineFit& fit) override;
  std::optional<JobRecord> claim(const MachineFit& fit, const std::string& machine,
                                 const Lease& lease) override;
  bool save_progress(int64_t id, const Lease& lease, const JobProgress& progress) override;
  bool finish(int64_t id, const Lease& lease, JobState state, const std::string& message,
              const JobProgress& progress) override;
  bool cancel(int64_t id) override;
  bool fail_queued(int64_t id, const std::string& message) override;
  bool requeue(int64_t id, bool continue_job) override;
  bool set_priority(int64_t id, int priority) override;
  Lease acquire_lease(const std::string& owner, const std::string& holder,
                      int64_t stale_ms) override;
  bool renew_lease(const Lease& lease) override;
  int interrupt_running(const std::string& owner, const std::string& message) override;
  int interrupt_stale(int64_t stale_ms, const std::string& message) override;

 private:
  struct Connection;  // pqxx::connection (a typedef in libpqxx 6: not forward-declarable)
  std::unique_ptr<Connection> conn_;
  std::mutex mutex_;  // a libpq connection serves one thread at a time
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_POSTGRES_JOB_STORE_H
