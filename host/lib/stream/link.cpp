// Link specs ("tcp://HOST:PORT", "serial:DEVICE[,BAUD]") and the Asio-backed links.
#include "host/lib/stream/link.h"

#include <asio.hpp>  // io_context, tcp socket, serial_port

#include <fmt/format.h>  // fmt::format

#include <stdexcept>  // std::invalid_argument
#include <utility>    // std::move

#include "host/lib/stream/host_port.h"  // the TCP address: parse_host_port, host_port_text

namespace host {

namespace {

const char kSpecForms[] = "expected tcp://HOST:PORT or serial:DEVICE[,BAUD]";

// Parses a decimal number in [lo, hi] or throws LinkError naming what it was for. Leading
// zeros are decimal ones, as in a URL: port 0080 is 80 (however many zeros).
unsigned parse_number(const std::string& text, unsigned lo, unsigned hi, const char* what,
                      const std::string& spec) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    throw LinkError(
        fmt::format("link '{}': {} '{}' is not a number ({})", spec, what, text, kSpecForms));
  }
  const size_t first = text.find_first_not_of('0');
  const std::string digits = first == std::string::npos ? "0" : text.substr(first);
  const unsigned long v = digits.size() > 9 ? hi + 1UL : std::stoul(digits);
  if (v < lo || v > hi) {
    throw LinkError(fmt::format("link '{}': {} {} outside {}..{}", spec, what, text, lo, hi));
  }
  return static_cast<unsigned>(v);
}

// One Asio stream (socket or serial port) with timed reads on its own io_context.
template <typename Stream>
class AsioLink : public Link {
 public:
  AsioLink(std::unique_ptr<asio::io_context> io, Stream stream, std::string name)
      : io_(std::move(io)), stream_(std::move(stream)), name_(std::move(name)) {}

  void write(const uint8_t* data, size_t size) override {
    asio::error_code ec;
    asio::write(stream_, asio::buffer(data, size), ec);
    if (ec) throw LinkError(fmt::format("{}: write failed: {}", name_, ec.message()));
  }

  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    asio::error_code result = asio::error::would_block;
    size_t got = 0;
    stream_.async_read_some(asio::buffer(buffer, capacity),
                            [&](const asio::error_code& ec, size_t n) {
                              result = ec;
                              got = n;
                            });
    io_->restart();
    io_->run_for(timeout);
    if (result == asio::error::would_block) {
      // Timed out: cancel and let the handler run so nothing refers to our locals.
      asio::error_code ignored;
      stream_.cancel(ignored);
      io_->restart();
      io_->run();
      if (result == asio::error::operation_aborted) return 0;
    }
    if (result == asio::error::operation_aborted) return got;
    if (result == asio::error::eof) throw LinkError(fmt::format("{}: closed by the peer", name_));
    if (result) throw LinkError(fmt::format("{}: read failed: {}", name_, result.message()));
    return got;
  }

  std::string name() const override { return name_; }

 private:
  std::unique_ptr<asio::io_context> io_;
  Stream stream_;
  std::string name_;
};

// Connects a TCP socket within the timeout or throws.
std::unique_ptr<Link> open_tcp(const LinkSpec& spec, std::chrono::milliseconds timeout) {
  auto io = std::make_unique<asio::io_context>();
  const std::string name = "tcp://" + host_port_text(spec.host, spec.port);
  asio::ip::tcp::resolver resolver(*io);
  asio::error_code ec;
  auto endpoints = resolver.resolve(spec.host, std::to_string(spec.port), ec);
  if (ec) throw LinkError(fmt::format("{}: cannot resolve host: {}", name, ec.message()));
  asio::ip::tcp::socket socket(*io);
  asio::error_code result = asio::error::would_block;
  asio::async_connect(
      socket, endpoints,
      [&](const asio::error_code& e, const asio::ip::tcp::endpoint&) { result = e; });
  io->run_for(timeout);
  if (result == asio::error::would_block) {
    socket.close();
    io->restart();
    io->run();
    throw LinkError(fmt::format("{}: no answer within {} ms", name, timeout.count()));
  }
  if (result) throw LinkError(fmt::format("{}: cannot connect: {}", name, result.message()));
  socket.set_option(asio::ip::tcp::no_delay(true));
  return std::make_unique<AsioLink<asio::ip::tcp::socket>>(std::move(io), std::move(socket), name);
}

// Opens and configures a serial port (8N1, no flow control) or throws.
std::unique_ptr<Link> open_serial(const LinkSpec& spec) {
  auto io = std::make_unique<asio::io_context>();
  const std::string name = fmt::format("serial:{},{}", spec.device, spec.baud);
  asio::serial_port port(*io);
  asio::error_code ec;
  port.open(spec.device, ec);
  if (ec) throw LinkError(fmt::format("{}: cannot open: {}", name, ec.message()));
  port.set_option(asio::serial_port_base::baud_rate(spec.baud), ec);
  if (!ec) port.set_option(asio::serial_port_base::character_size(8), ec);
  if (!ec)
    port.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
  if (!ec) {
    port.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one), ec);
  }
  if (!ec) {
    port.set_option(
        asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
  }
  if (ec) throw LinkError(fmt::format("{}: cannot configure: {}", name, ec.message()));
  return std::make_unique<AsioLink<asio::serial_port>>(std::move(io), std::move(port), name);
}

}  // namespace

LinkSpec parse_link_spec(const std::string& spec) {
  LinkSpec out;
  const std::string tcp = "tcp://";
  const std::string serial = "serial:";
  if (spec.compare(0, tcp.size(), tcp) == 0) {
    out.kind = LinkSpec::kTcp;
    try {
      const HostPort hp = parse_host_port(spec.substr(tcp.size()), PortUse::kConnect);
      out.host = hp.host;
      out.port = hp.port;
    } catch (const std::invalid_argument& e) {
      // Refused here, as the command line is read, not as a host not found after planning.
      throw LinkError(fmt::format("link '{}': {} ({})", spec, e.what(), kSpecForms));
    }
    return out;
  }
  if (spec.compare(0, serial.size(), serial) == 0) {
    const std::string rest = spec.substr(serial.size());
    const size_t comma = rest.find(',');
    out.kind = LinkSpec::kSerial;
    out.device = rest.substr(0, comma);
    if (out.device.empty())
      throw LinkError(fmt::format("link '{}': no device ({})", spec, kSpecForms));
    if (comma != std::string::npos) {
      out.baud = parse_number(rest.substr(comma + 1), 1200, 4000000, "baud rate", spec);
    }
    return out;
  }
  throw LinkError(fmt::format("link '{}': unknown kind ({})", spec, kSpecForms));
}

std::unique_ptr<Link> open_link(const LinkSpec& spec, std::chrono::milliseconds connect_timeout) {
  return spec.kind == LinkSpec::kTcp ? open_tcp(spec, connect_timeout) : open_serial(spec);
}

}  // namespace host
