// The job store in one SQLite file (the data folder's jobs.sqlite): a single workshop PC.
#ifndef HOST_LIB_SERVER_SQLITE_JOB_STORE_H
#define HOST_LIB_SERVER_SQLITE_JOB_STORE_H

#include <memory>  // std::unique_ptr
#include <mutex>   // std::mutex
#include <string>  // std::string

#include "host/lib/server/job_store.h"

struct sqlite3;

namespace host::server {

class SqliteJobStore : public JobStore {
 public:
  // Opens (creates) the database file. Throws StoreError naming the file.
  explicit SqliteJobStore(const std::string& path);
  ~SqliteJobStore() override;
  SqliteJobStore(const SqliteJobStore&) = delete;
  SqliteJobStore& operator=(const SqliteJobStore&) = delete;

  int64_t add(const JobRecord& job, const std::string& input) override;
  std::optional<std::string> input(int64_t) override { return std::nullopt; }
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
  void exec(const std::string& sql);
  bool has_column(const char* table, const char* column);
  void add_missing_columns();
  std::string path_;
  sqlite3* db_ = nullptr;
  std::mutex mutex_;  // one statement sequence at a time (claim is select + update)
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_SQLITE_JOB_STORE_H
