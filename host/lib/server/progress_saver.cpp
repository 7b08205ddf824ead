// Progress from the controller's status, and the thread that saves it.
#include "host/lib/server/progress_saver.h"

#include <algorithm>  // std::min

#include "host/lib/stream/job_resume.h"  // resume_point_of

namespace host::server {

using Clock = std::chrono::steady_clock;

int first_uncut_curve(const std::vector<QueuedCommand>& sent, size_t executed) {
  for (size_t i = executed; i < sent.size(); ++i) {
    if (sent[i].curve >= 0) return sent[i].curve;
  }
  return -1;
}

JobProgress progress_of(JobProgress known, size_t total, size_t executed, int first_uncut,
                        const proto::StatusReply& status, uint16_t job_id) {
  known.executed = static_cast<int64_t>(executed);
  known.total = static_cast<int64_t>(total);
  known.resume_curve = first_uncut;
  const std::optional<ResumePoint> at = resume_point_of(status);
  // Before our #J has been taken, the status still tells the previous job's progress.
  if (at && at->job_id == job_id) {
    known.resume_index = at->job_index;
    known.resume_point = at->curve_point;
    known.resume_job_id = at->job_id;
  }
  return known;
}

ProgressSaver::ProgressSaver(JobStore& store, std::chrono::milliseconds interval,
                             std::function<void(int64_t)> on_refused)
    : store_(store), interval_(interval), on_refused_(std::move(on_refused)) {
  thread_ = std::thread([this] { loop(); });
}

ProgressSaver::~ProgressSaver() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void ProgressSaver::post(int64_t job_id, const Lease& lease, const JobProgress& progress,
                         bool urgent) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Entry& e = jobs_[job_id];
    e.lease = lease;
    e.progress = progress;
    e.pending = true;
    e.urgent = e.urgent || urgent;
  }
  cv_.notify_all();
}

void ProgressSaver::forget(int64_t job_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  jobs_.erase(job_id);
}

uint64_t ProgressSaver::writes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return writes_;
}

void ProgressSaver::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    // The job most overdue, or how long until one is due.
    const Clock::time_point now = Clock::now();
    Clock::time_point next = now + std::chrono::hours(1);
    int64_t due_id = 0;
    for (const auto& [id, e] : jobs_) {
      if (!e.pending) continue;
      const Clock::time_point due = e.urgent ? now : e.last_write + interval_;
      if (due <= now) {
        due_id = id;
        break;
      }
      next = std::min(next, due);
    }
    if (due_id == 0) {
      cv_.wait_until(lock, next);
      continue;
    }
    Entry& e = jobs_[due_id];
    const Lease lease = e.lease;
    const JobProgress progress = e.progress;
    e.pending = e.urgent = false;
    e.last_write = now;
    lock.unlock();
    bool refused = false;
    try {
      refused = !store_.save_progress(due_id, lease, progress);
    } catch (const StoreError&) {
      // The database is away: the next position is tried after the interval.
    }
    if (refused && on_refused_) on_refused_(due_id);
    lock.lock();
    ++writes_;
  }
}

}  // namespace host::server
