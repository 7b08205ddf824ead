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

// Another live server holds the name (PostgreSQL: same --name on another PC or folder).
class NameInUse : public StoreError {
 public:
  explicit NameInUse(const std::string& msg) : StoreError(msg) {}
};

// The lease a claim or a running job's update named is gone: the server was taken for dead
// (silent longer than stale_after) and its jobs were interrupted.
class LeaseLost : public StoreError {
 public:
  explicit LeaseLost(const std::string& msg) : StoreError(msg) {}
};

// A server's claim on its name. The epoch grows each time the name is taken, so a server that
// was taken for dead (and whose name was taken again, or revoked) can change nothing under
// its old lease: every change to a job it runs names the lease and is refused once it is gone.
struct Lease {
  std::string owner;
  int64_t epoch = 0;
};

// How far a running job got: saved while it runs and when it ends.
struct JobProgress {
  int64_t executed = 0;       // commands of the stream sent executed
  int64_t total = 0;          // commands in that stream
  int resume_curve = -1;      // first plan curve not fully cut (-1: none)
  int64_t resume_index = -1;  // JobRecord::resume_index (-1: not known)
  int resume_point = 0;
  int resume_job_id = -1;
};

class JobStore {
 public:
  virtual ~JobStore() = default;
  // Stores a new job (id, created_ms assigned here) and returns its id. `input` is the
  // uploaded file: a store shared by several servers keeps it so that any of them can run
  // the job; a local store may ignore it (the archive folder has it).
  virtual int64_t add(const JobRecord& job, const std::string& input) = 0;
  // Whether add() keeps `input`: when not, the intake passes "" (a drawing's bytes are not
  // read into memory for nothing).
  virtual bool keeps_input() const { return true; }
  // The uploaded file, when this store keeps it (see add).
  virtual std::optional<std::string> input(int64_t id) = 0;
  virtual std::optional<JobRecord> get(int64_t id) = 0;
  // Newest first; state_filter "" = every state.
  virtual std::vector<JobRecord> list(const std::string& state_filter, size_t limit) = 0;
  // Whether a queued job fits (cheap; a machine asks before it opens its link).
  virtual bool has_claimable(const MachineFit& fit) = 0;
  // Takes the best queued job that fits (priority, then age) and marks it running on
  // `machine` under `lease`, atomically. None when nothing fits; LeaseLost when the lease is
  // gone.
  virtual std::optional<JobRecord> claim(const MachineFit& fit, const std::string& machine,
                                         const Lease& lease) = 0;
  // Where a running job has got to. False when it is not running under `lease` any more
  // (interrupted by another server: stop sending it).
  virtual bool save_progress(int64_t id, const Lease& lease, const JobProgress& progress) = 0;
  // A running job ended (completed/aborted/failed/interrupted). False if it was not running
  // under `lease`.
  virtual bool finish(int64_t id, const Lease& lease, JobState state, const std::string& message,
                      const JobProgress& progress) = 0;
  // Queued -> cancelled. False when the job is not queued.
  virtual bool cancel(int64_t id) = 0;
  // Queued -> failed with `message`, never claimed (no machine, no run): a job that cannot
  // run (its height map's source job ended without one). False when the job is not queued.
  virtual bool fail_queued(int64_t id, const std::string& message) = 0;
  // Interrupted, aborted or failed -> queued again, from the start or (continue_job, an
  // interrupted job whose position is known: resume_index or resume_curve) from where it
  // stopped; an interrupted job with nothing executed and no position (stopped before its
  // first save) continues from the start. False otherwise.
  virtual bool requeue(int64_t id, bool continue_job) = 0;
  // Changes a queued job's priority. False when the job is not queued.
  virtual bool set_priority(int64_t id, int priority) = 0;
  // Takes the name `owner` for this server with a new epoch. `holder` says who holds it
  // (host and data folder): a live lease (renewed within stale_ms) of another holder is
  // refused with NameInUse; one of the same holder is taken over (its process is gone: the
  // data folder's lock says so).
  virtual Lease acquire_lease(const std::string& owner, const std::string& holder,
                              int64_t stale_ms) = 0;
  // This server is alive (every second or so). False: the lease is gone.
  virtual bool renew_lease(const Lease& lease) = 0;
  // At start-up: jobs this owner left running (the server died) become interrupted.
  // Returns how many.
  virtual int interrupt_running(const std::string& owner, const std::string& message) = 0;
  // Leases not renewed for stale_ms are revoked, and running jobs not under a standing lease
  // become interrupted, in one transaction: a server that died (or froze) mid-job loses no
  // job and, if it wakes, can change none of them. Returns how many jobs.
  virtual int interrupt_stale(int64_t stale_ms, const std::string& message) = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_STORE_H
