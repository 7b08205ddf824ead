// TCP or serial-device front of the simulated machine: accept, tunnel bytes, pace machine
// time (the rules are in sim_server.h).
#include "host/lib/sim/sim_server.h"

#include <asio.hpp>  // tcp acceptor and socket

#include <fcntl.h>       // open
#include <poll.h>        // poll
#include <sys/socket.h>  // send, MSG_NOSIGNAL
#include <termios.h>     // raw mode for a device
#include <unistd.h>      // read, write, close

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::max
#include <cerrno>     // errno
#include <chrono>     // steady_clock
#include <cstring>    // std::strerror
#include <stdexcept>  // std::runtime_error
#include <thread>     // sleep_for

#include "host/lib/stream/host_port.h"  // host_port_text: [::1]:10001

namespace host::sim {

using Clock = std::chrono::steady_clock;

constexpr uint64_t kSocketEveryMs = 4;  // fast mode looks at the host every 4 machine ms

struct SimServer::Impl {
  Impl(SimMachine& m, const ServerOptions& o) : machine(m), options(o), acceptor(io) {}
  ~Impl() {
    if (device_fd >= 0) ::close(device_fd);
  }
  SimMachine& machine;
  ServerOptions options;
  asio::io_context io;
  asio::ip::tcp::acceptor acceptor;
  std::unique_ptr<asio::ip::tcp::socket> client;
  int device_fd = -1;
  uint64_t last_host_ms = 0;  // machine time of the connection (counts as the host speaking)

  bool connected() const { return client != nullptr || device_fd >= 0; }
  int fd() const { return client ? client->native_handle() : device_fd; }

  // Moves what the host sent into the machine. False when a TCP connection closed.
  bool receive() {
    uint8_t buf[1024];
    while (true) {
      const ssize_t n = ::read(fd(), buf, sizeof buf);
      if (n > 0) {
        machine.from_host(buf, static_cast<size_t>(n));
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return true;
      // A device whose other end is closed reads as EOF or EIO: wait for it to be opened.
      return device_fd >= 0;
    }
  }

  // Sends what the firmware transmitted. False when the connection broke. A socket whose
  // client hung up must not raise SIGPIPE (it would end `engraver sim`): MSG_NOSIGNAL.
  bool transmit() {
    const std::string out = machine.take_to_host();
    size_t at = 0;
    while (at < out.size()) {
      const ssize_t n = client ? ::send(fd(), out.data() + at, out.size() - at, MSG_NOSIGNAL)
                               : ::write(fd(), out.data() + at, out.size() - at);
      if (n > 0) {
        at += static_cast<size_t>(n);
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
        pollfd p{fd(), POLLOUT, 0};
        ::poll(&p, 1, 100);
        continue;
      }
      return device_fd >= 0;  // a device with nobody on the other end: the bytes are lost
    }
    return true;
  }

  // Blocks until the host has bytes (or closed) or timeout_ms passes; returns poll's revents.
  int wait_readable(int timeout_ms) {
    pollfd p{fd(), POLLIN, 0};
    return ::poll(&p, 1, timeout_ms) > 0 ? p.revents : 0;
  }

  // A departed client's unread frames must not run after it, nor its replies go to the
  // next client: dropped (the machine then meets the silence of a lost link).
  void drop_client() {
    asio::error_code ignored;
    client->close(ignored);
    client.reset();
    machine.drop_link_bytes();
  }

  // Accepts a pending connection, if any, without blocking.
  void try_accept() {
    if (device_fd >= 0) return;
    asio::error_code ec;
    asio::ip::tcp::socket s(io);
    acceptor.accept(s, ec);
    if (ec) return;
    s.non_blocking(true, ec);
    s.set_option(asio::ip::tcp::no_delay(true), ec);
    client = std::make_unique<asio::ip::tcp::socket>(std::move(s));
    machine.drop_link_bytes();  // what the firmware said to nobody meanwhile
    last_host_ms = machine.now_ms();
  }
};

namespace {

// Opens a serial device raw (8N1, no echo, no line discipline), non-blocking.
int open_device(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd < 0)
    throw std::runtime_error(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  termios t{};
  if (tcgetattr(fd, &t) == 0) {
    cfmakeraw(&t);
    cfsetispeed(&t, B115200);
    cfsetospeed(&t, B115200);
    t.c_cflag |= CLOCAL | CREAD;
    tcsetattr(fd, TCSANOW, &t);
  }
  return fd;
}

}  // namespace

SimServer::SimServer(SimMachine& machine, const ServerOptions& options)
    : impl_(std::make_unique<Impl>(machine, options)) {
  // The client's bytes come in wall-clock time, however fast machine time runs between them:
  // the firmware's link time-outs count the wall clock, as on the real controller.
  machine.set_link_time(SimMachine::LinkTime::kWall);
  if (!options.device.empty()) {
    impl_->device_fd = open_device(options.device);
    return;
  }
  asio::error_code ec;
  const asio::ip::address addr = asio::ip::make_address(options.address, ec);
  if (ec)
    throw std::runtime_error(fmt::format("listen address '{}': {}", options.address, ec.message()));
  const asio::ip::tcp::endpoint ep(addr, options.port);
  impl_->acceptor.open(ep.protocol(), ec);
  if (!ec) impl_->acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  if (!ec) impl_->acceptor.bind(ep, ec);
  if (!ec) impl_->acceptor.listen(1, ec);
  if (!ec) impl_->acceptor.non_blocking(true, ec);
  if (ec) {
    throw std::runtime_error(fmt::format(
        "cannot listen on {}: {}", host_port_text(options.address, options.port), ec.message()));
  }
}

SimServer::~SimServer() = default;

uint16_t SimServer::port() const {
  return impl_->device_fd >= 0 ? 0 : impl_->acceptor.local_endpoint().port();
}

uint64_t SimServer::run(const std::atomic<bool>& stop) {
  Impl& s = *impl_;
  const uint64_t start_ms = s.machine.now_ms();
  // Following the wall clock: machine time pace_ms was due at wall time pace_wall.
  bool paced = false;
  uint64_t pace_ms = 0;
  Clock::time_point pace_wall;
  while (!stop) {
    if (!s.connected()) s.try_accept();
    if (!s.connected() && !s.machine.busy()) {
      // Nobody connected and nothing moving: nothing would change; wait for a host.
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      paced = false;
      continue;
    }
    const uint64_t now = s.machine.now_ms();
    const uint64_t last = std::max(s.last_host_ms, s.machine.last_host_byte_ms());
    const bool fast = !s.options.realtime && s.connected() &&
                      (s.machine.host_bytes_waiting() || now - last < s.options.fast_window_ms);
    if (fast) {
      paced = false;
      if (now % kSocketEveryMs == 0 && !s.receive()) s.drop_client();
    } else {
      if (!paced) {
        paced = true;
        pace_ms = now;
        pace_wall = Clock::now();
      }
      const auto due = pace_wall + std::chrono::milliseconds(now - pace_ms);
      // Wait for the wall clock, taking the host's bytes as they come; in fast mode they end
      // the wait (the host speaks again).
      while (s.connected()) {
        const auto left = due - Clock::now();
        if (left <= Clock::duration::zero()) {
          // Behind the wall clock (a busy computer): catching up, still take the host's
          // bytes, as the real UART does; else a machine slower than real time hears nothing
          // and answers nothing (the host's "no reply for 10000 ms").
          if (!s.receive()) s.drop_client();
          break;
        }
        const int wait_ms =
            static_cast<int>(std::chrono::ceil<std::chrono::milliseconds>(left).count());
        if (s.wait_readable(wait_ms) & POLLHUP && s.device_fd >= 0) {
          std::this_thread::sleep_until(due);  // nobody on the device's other end yet
          break;
        }
        if (!s.receive()) {
          s.drop_client();
          break;
        }
        if (!s.options.realtime && s.machine.host_bytes_waiting()) break;
      }
      if (!s.connected()) std::this_thread::sleep_until(due);
    }
    s.machine.step_ms();
    if (s.connected() && !s.transmit()) s.drop_client();
  }
  if (s.client) s.drop_client();
  return s.machine.now_ms() - start_ms;
}

}  // namespace host::sim
