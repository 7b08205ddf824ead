// A TCP proxy on loopback for tests: a network that stops for a while and comes back.
#pragma once

#include <fmt/format.h>  // fmt::format
#include <netinet/in.h>  // sockaddr_in
#include <poll.h>        // poll
#include <sys/socket.h>  // socket, accept, connect
#include <unistd.h>      // read, write, close

#include <atomic>  // std::atomic
#include <chrono>  // std::chrono
#include <string>  // std::string
#include <thread>  // std::thread

namespace host::test {

// A TCP proxy on loopback to `port` that, frozen, passes no byte either way (the connection
// stays open): a network that stops for a while.
class FreezingProxy {
 public:
  explicit FreezingProxy(uint16_t port) : to_(port) {
    listen_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t n = sizeof a;
    ::bind(listen_, reinterpret_cast<sockaddr*>(&a), n);
    ::listen(listen_, 4);
    ::getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &n);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~FreezingProxy() {
    stop_ = true;
    thread_.join();
    ::close(listen_);
  }
  std::string address() const { return fmt::format("tcp://127.0.0.1:{}", port_); }
  void freeze(bool on) { frozen_ = on; }

 private:
  void serve() {
    while (!stop_) {
      pollfd p{listen_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      const int client = ::accept(listen_, nullptr, nullptr);
      const int machine = ::socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      a.sin_port = htons(to_);
      if (::connect(machine, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) pass(client, machine);
      ::close(machine);
      ::close(client);
    }
  }
  // Both ways until either side closes (or the proxy stops).
  void pass(int client, int machine) {
    char buf[4096];
    while (!stop_) {
      if (frozen_) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      pollfd p[2] = {{client, POLLIN, 0}, {machine, POLLIN, 0}};
      if (::poll(p, 2, 20) <= 0) continue;
      for (int i = 0; i < 2; ++i) {
        if (!(p[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        const ssize_t n = ::read(p[i].fd, buf, sizeof buf);
        if (n <= 0 || ::write(p[1 - i].fd, buf, n) != n) return;
      }
    }
  }
  uint16_t to_, port_ = 0;
  int listen_ = -1;
  std::atomic<bool> frozen_{false}, stop_{false};
  std::thread thread_;
};

}  // namespace host::test
