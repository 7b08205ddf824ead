// What other threads and signal handlers ask of a running sender (hold, resume, abort, feed
// override), kept until the sender's loop takes them; lock-free, so a signal handler may set
// them.
#ifndef HOST_LIB_STREAM_OPERATOR_REQUESTS_H
#define HOST_LIB_STREAM_OPERATOR_REQUESTS_H

#include <atomic>  // std::atomic

namespace host {

class OperatorRequests {
 public:
  void hold() { hold_ = true; }
  void resume() { resume_ = true; }
  // `why` says who stopped the job, as its message begins ("aborted by the operator",
  // "stopped by SIGTERM"); a string literal, so that a signal handler may give one.
  void abort(const char* why) {
    why_ = why;
    abort_ = true;
  }
  void override_percent(int percent) { override_ = percent; }

  // The sender's side: each take_ clears what it returns; an abort stays asked.
  bool abort_asked() const { return abort_; }
  const char* abort_cause() const { return why_; }
  bool take_hold() { return hold_.exchange(false); }
  bool take_resume() { return resume_.exchange(false); }
  int take_override() { return override_.exchange(0); }  // 0: none

 private:
  std::atomic<bool> hold_{false};
  std::atomic<bool> resume_{false};
  std::atomic<bool> abort_{false};
  std::atomic<const char*> why_{""};
  std::atomic<int> override_{0};
};

}  // namespace host

#endif  // HOST_LIB_STREAM_OPERATOR_REQUESTS_H
