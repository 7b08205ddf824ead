// A running job's position, saved to the store while it runs so that "continue" works after
// any crash: the job command and curve point the controller reports (docs/protocol.md, #J and
// the status), written from a thread of its own at most once per interval per job (the newest
// position wins; a hold or another change of machine state at once), so a slow or unreachable
// database never stalls a machine's sender.
#ifndef HOST_LIB_SERVER_PROGRESS_SAVER_H
#define HOST_LIB_SERVER_PROGRESS_SAVER_H

#include <chrono>              // std::chrono
#include <condition_variable>  // std::condition_variable
#include <cstdint>             // int64_t
#include <functional>          // std::function
#include <map>                 // std::map
#include <mutex>               // std::mutex
#include <thread>              // std::thread
#include <vector>              // std::vector

#include "firmware/protocol/messages.h"  // proto::StatusReply
#include "host/lib/server/job_store.h"
#include "host/lib/stream/job_encoder.h"  // QueuedCommand

namespace host::server {

// `known` updated from a status of a stream of `total` commands (of which `executed` have
// run; first_uncut: the curve of the first not executed, -1 none): counts and first uncut
// curve always; the controller's position when the status is about this job (its whole
// stream's job_id is `job_id`); else the last one known stays.
JobProgress progress_of(JobProgress known, size_t total, size_t executed, int first_uncut,
                        const proto::StatusReply& status, uint16_t job_id);
// The curve of the first command of `sent` not executed (-1: none left).
int first_uncut_curve(const std::vector<QueuedCommand>& sent, size_t executed);

class ProgressSaver {
 public:
  // on_refused(job id): the store refused a save (the job no longer runs under its lease).
  ProgressSaver(JobStore& store, std::chrono::milliseconds interval,
                std::function<void(int64_t)> on_refused);
  ~ProgressSaver();
  ProgressSaver(const ProgressSaver&) = delete;
  ProgressSaver& operator=(const ProgressSaver&) = delete;

  // The newest position of a running job; `urgent`: without waiting for the interval.
  void post(int64_t job_id, const Lease& lease, const JobProgress& progress, bool urgent);
  // The job ended (its end is saved with JobStore::finish): drops what is not written yet.
  void forget(int64_t job_id);
  // Saves written so far (for the log and tests).
  uint64_t writes() const;

 private:
  struct Entry {
    Lease lease;
    JobProgress progress;
    bool pending = false;
    bool urgent = false;
    std::chrono::steady_clock::time_point last_write{};
  };
  void loop();

  JobStore& store_;
  const std::chrono::milliseconds interval_;
  std::function<void(int64_t)> on_refused_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::map<int64_t, Entry> jobs_;
  uint64_t writes_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_PROGRESS_SAVER_H
