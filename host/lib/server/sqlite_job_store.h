// The job store in one SQLite file (the data folder's jobs.sqlite): a single workshop PC.
#ifndef HOST_LIB_SERVER_SQLITE_JOB_STORE_H
#define HOST_LIB_SERVER_SQLITE_JOB_STORE_H

#include <memory>  // std::unique_ptr
#include <mutex>   // std::mutex
#include <string>  // std::string

#include "host/lib/server/sql_job_store.h"

struct sqlite3;

namespace host::server {

class SqliteJobStore : public SqlJobStore {
 public:
  // Opens (creates) the database file. Throws StoreError naming the file.
  explicit SqliteJobStore(const std::string& path);
  ~SqliteJobStore() override;
  SqliteJobStore(const SqliteJobStore&) = delete;
  SqliteJobStore& operator=(const SqliteJobStore&) = delete;

  int64_t add(const JobRecord& job, const std::string& input) override;
  std::optional<std::string> input(int64_t) override { return std::nullopt; }
  bool keeps_input() const override { return false; }  // the archive folder has it
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
  void exec(const std::string& sql);
  bool has_column(const char* table, const char* column);
  void add_missing_columns();
  std::string path_;
  sqlite3* db_ = nullptr;
  std::mutex mutex_;  // one statement sequence at a time (claim is select + update)
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_SQLITE_JOB_STORE_H
