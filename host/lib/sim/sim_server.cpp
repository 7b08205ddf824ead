// TCP front of the simulated machine: accept, tunnel bytes, pace virtual time.
#include "host/lib/sim/sim_server.h"

#include <asio.hpp>  // tcp acceptor and socket

#include <fmt/format.h>  // fmt::format

#include <chrono>     // steady_clock
#include <stdexcept>  // std::runtime_error
#include <thread>     // sleep_for

#include <poll.h>  // poll

namespace host::sim {

using Clock = std::chrono::steady_clock;

constexpr uint64_t kSocketEveryMs = 4;

struct SimServer::Impl {
  Impl(SimMachine& m, const ServerOptions& o) : machine(m), options(o), acceptor(io) {}
  SimMachine& machine;
  ServerOptions options;
  asio::io_context io;
  asio::ip::tcp::acceptor acceptor;
  std::unique_ptr<asio::ip::tcp::socket> client;
  uint64_t last_host_byte_ms = 0;

  // Moves what the host sent into the machine. False when the connection closed.
  bool receive() {
    uint8_t buf[1024];
    asio::error_code ec;
    while (true) {
      const size_t avail = client->available(ec);
      if (ec) return false;
      if (avail == 0) {
        // available() says 0 both for "nothing yet" and "closed": a non-blocking read tells.
        const size_t n = client->read_some(asio::buffer(buf, 1), ec);
        if (ec == asio::error::would_block) return true;
        if (ec) return false;
        machine.from_host(buf, n);
        last_host_byte_ms = machine.now_ms();
        continue;
      }
      const size_t n = client->read_some(asio::buffer(buf, std::min(avail, sizeof buf)), ec);
      if (ec) return ec == asio::error::would_block;
      machine.from_host(buf, n);
      last_host_byte_ms = machine.now_ms();
    }
  }

  // Sends what the firmware transmitted. False when the connection broke.
  bool transmit() {
    const std::string out = machine.take_to_host();
    if (out.empty()) return true;
    asio::error_code ec;
    client->non_blocking(false);
    asio::write(*client, asio::buffer(out), ec);
    client->non_blocking(true);
    return !ec;
  }

  // Blocks until the client has bytes (or closed) or timeout_ms passes.
  void wait_readable(int timeout_ms) {
    pollfd p{client->native_handle(), POLLIN, 0};
    ::poll(&p, 1, timeout_ms);
  }

  void drop_client() {
    asio::error_code ignored;
    client->close(ignored);
    client.reset();
  }

  // Accepts a pending connection, if any, without blocking.
  void try_accept() {
    asio::error_code ec;
    asio::ip::tcp::socket s(io);
    acceptor.accept(s, ec);
    if (ec) return;
    s.non_blocking(true, ec);
    s.set_option(asio::ip::tcp::no_delay(true), ec);
    client = std::make_unique<asio::ip::tcp::socket>(std::move(s));
    last_host_byte_ms = machine.now_ms();
  }
};

SimServer::SimServer(SimMachine& machine, const ServerOptions& options)
    : impl_(std::make_unique<Impl>(machine, options)) {
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
    throw std::runtime_error(
        fmt::format("cannot listen on {}:{}: {}", options.address, options.port, ec.message()));
  }
}

SimServer::~SimServer() = default;

uint16_t SimServer::port() const {
  return impl_->acceptor.local_endpoint().port();
}

uint64_t SimServer::run(const std::atomic<bool>& stop) {
  Impl& s = *impl_;
  const uint64_t start_ms = s.machine.now_ms();
  const auto wall_start = Clock::now();
  while (!stop) {
    // The socket is looked at every few machine milliseconds: the UART takes 11.5 bytes a
    // millisecond, so a 4 ms batch delays nothing a real link would not.
    const bool look = s.machine.now_ms() % kSocketEveryMs == 0;
    if (!s.client) s.try_accept();
    if (s.client && look && !s.receive()) s.drop_client();

    const bool silent =
        s.client && s.machine.now_ms() - s.last_host_byte_ms >= s.options.max_silent_ms;
    if (!s.client && !s.machine.busy() && !s.options.realtime) {
      // Nobody connected and nothing moving: nothing would change; wait for a host.
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    if (silent && !s.options.realtime) {
      // A connected host that has said nothing for a while: give it real time to speak
      // before machine time moves on (at most one virtual ms per 5 real ms while silent).
      s.wait_readable(5);
      if (s.client && !s.receive()) s.drop_client();
    }
    s.machine.step_ms();
    if (s.client && !s.transmit()) s.drop_client();
    if (s.options.realtime) {
      const auto due = wall_start + std::chrono::milliseconds(s.machine.now_ms() - start_ms);
      std::this_thread::sleep_until(due);
    }
  }
  if (s.client) s.drop_client();
  return s.machine.now_ms() - start_ms;
}

}  // namespace host::sim
