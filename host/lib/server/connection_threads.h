// cpp-httplib's task queue for the workshop server: one thread per open connection instead
// of a fixed pool, so that long-lived event streams (one per open page) never leave a
// control request waiting for a free thread.
#ifndef HOST_LIB_SERVER_CONNECTION_THREADS_H
#define HOST_LIB_SERVER_CONNECTION_THREADS_H

#include <httplib.h>  // httplib::TaskQueue

#include <condition_variable>  // std::condition_variable
#include <cstddef>             // size_t
#include <functional>          // std::function
#include <mutex>               // std::mutex

namespace host::server {

class ConnectionThreads : public httplib::TaskQueue {
 public:
  // stack_bytes: each connection's thread (handlers parse JSON and match routes; 1 MB is
  // ample and keeps 1 000 open pages at 1 GB of address space, little of it touched).
  explicit ConnectionThreads(size_t stack_bytes = 1024 * 1024) : stack_bytes_(stack_bytes) {}
  ~ConnectionThreads() override { shutdown(); }
  // Runs fn (one connection: its requests, then close) on a new detached thread.
  void enqueue(std::function<void()> fn) override;
  // Waits until every connection's thread has ended (httplib calls this after stop()).
  void shutdown() override;
  size_t live() const;

 private:
  void finished();
  size_t stack_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable all_done_;
  size_t live_ = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_CONNECTION_THREADS_H
