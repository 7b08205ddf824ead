#include "host/lib/server/listen_check.h"

#include <fmt/format.h>  // fmt::format

#include <asio.hpp>   // tcp acceptor
#include <stdexcept>  // std::runtime_error

#include "host/lib/stream/host_port.h"  // host_port_text

namespace host::server {

std::string cannot_listen_text(const std::string& address, int port) {
  return fmt::format("cannot listen on {} (in use or not an address of this PC)",
                     host_port_text(address, port));
}

void check_can_listen(const std::string& address, int port) {
  if (port == 0) return;
  asio::io_context io;
  asio::ip::tcp::acceptor acceptor(io);
  asio::error_code ec;
  const asio::ip::address addr = asio::ip::make_address(address, ec);
  if (ec) throw std::runtime_error(cannot_listen_text(address, port));
  const asio::ip::tcp::endpoint ep(addr, static_cast<uint16_t>(port));
  // As the server binds: SO_REUSEADDR (a restart right after a stop), never SO_REUSEPORT.
  acceptor.open(ep.protocol(), ec);
  if (!ec) acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  if (!ec) acceptor.bind(ep, ec);
  if (!ec) acceptor.listen(1, ec);
  if (ec) throw std::runtime_error(cannot_listen_text(address, port));
}

}  // namespace host::server
