// Where the queue and the archive records live: one interface, an SQLite file for one
// workshop PC (and PostgreSQL for several servers on one queue). Every change a caller makes
// is one atomic step, so two machines (or two servers) never claim the same job.
#ifndef HOST_LIB_SERVER_JOB_STORE_H
#define HOST_LIB_SERVER_JOB_STORE_H

#include <cstdint>    // int64_t
#include <optional>   // std::optional
#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/lib/server/job_record.h"

namespace host::server {

// The database failed (cannot open, disk full, ...). what() names the database and the cause.
class StoreError : public std::runtime_error {
 public:
  explicit StoreError(const std::string& msg) : std::runtime_error(msg) {}
};

class JobStore {
 public:
  virtual ~JobStore() = default;
  // Stores a new job (id, created_ms assigned here) and returns its id. `input` is the
  // uploaded file: a store shared by several servers keeps it so that any of them can run
  // the job; a local store may ignore it (the archive folder has it).
  virtual int64_t add(const JobRecord& job, const std::string& input) = 0;
  // The uploaded file, when this store keeps it (see add).
  virtual std::optional<std::string> input(int64_t id) = 0;
  virtual std::optional<JobRecord> get(int64_t id) = 0;
  // Newest first; state_filter "" = every state.
  virtual std::vector<JobRecord> list(const std::string& state_filter, size_t limit) = 0;
  // Whether a queued job fits (cheap; a machine asks before it opens its link).
  virtual bool has_claimable(const MachineFit& fit) = 0;
  // Takes the best queued job that fits (priority, then age) and marks it running on
  // `machine` for `owner`, atomically. None when nothing fits.
  virtual std::optional<JobRecord> claim(const MachineFit& fit, const std::string& machine,
                                         const std::string& owner) = 0;
  // A running job ended (completed/aborted/failed/interrupted). False if it was not running.
  virtual bool finish(int64_t id, JobState state, const std::string& message, int64_t executed,
                      int64_t total, int resume_curve) = 0;
  // Queued -> cancelled. False when the job is not queued.
  virtual bool cancel(int64_t id) = 0;
  // Interrupted, aborted or failed -> queued again, from the start or (continue_job, an
  // interrupted job with a known resume_curve) from its first uncut curve. False otherwise.
  virtual bool requeue(int64_t id, bool continue_job) = 0;
  // Changes a queued job's priority. False when the job is not queued.
  virtual bool set_priority(int64_t id, int priority) = 0;
  // At start-up: jobs this owner left running (the server died) become interrupted.
  // Returns how many.
  virtual int interrupt_running(const std::string& owner, const std::string& message) = 0;
  // This server is alive (called every second or so by each server sharing the store).
  virtual void heartbeat(const std::string& owner) = 0;
  // Running jobs of servers not heard from since `cutoff_ms` (Unix ms) become interrupted:
  // a server that died mid-job loses no job. Returns how many.
  virtual int interrupt_stale(int64_t cutoff_ms, const std::string& message) = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_STORE_H
