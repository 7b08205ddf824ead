// One thread per connection for cpp-httplib (see connection_threads.h).
#include "host/lib/server/connection_threads.h"

#include <pthread.h>  // pthread_create, pthread_attr_setstacksize

#include <memory>  // std::unique_ptr

namespace host::server {

namespace {

struct Start {
  std::function<void()> fn;
  std::function<void()> done;
};

extern "C" void* run_connection(void* arg) {
  std::unique_ptr<Start> start(static_cast<Start*>(arg));
  start->fn();
  start->done();
  return nullptr;
}

}  // namespace

void ConnectionThreads::enqueue(std::function<void()> fn) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++live_;
  }
  auto start = std::make_unique<Start>(Start{std::move(fn), [this] { finished(); }});
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, stack_bytes_);
  pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
  pthread_t thread;
  const int err = pthread_create(&thread, &attr, run_connection, start.get());
  pthread_attr_destroy(&attr);
  if (err == 0) {
    start.release();  // the thread owns it now
    return;
  }
  // No thread to be had (the system's limit): serve it here, so that its socket is still
  // answered and closed; the accept loop waits meanwhile.
  run_connection(start.release());
}

void ConnectionThreads::finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (--live_ == 0) all_done_.notify_all();
}

void ConnectionThreads::shutdown() {
  std::unique_lock<std::mutex> lock(mutex_);
  all_done_.wait(lock, [&] { return live_ == 0; });
}

size_t ConnectionThreads::live() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return live_;
}

}  // namespace host::server
