// ADDR:PORT for every TCP address of the tool (see host_port.h).
#include "host/lib/stream/host_port.h"

#include <asio/ip/address.hpp>  // make_address_v4, make_address_v6

#include <fmt/format.h>  // fmt::format

#include <stdexcept>  // std::invalid_argument

namespace host {

namespace {

// A numeric address of the given family; a host name is neither.
bool is_ipv4(const std::string& host) {
  asio::error_code ec;
  asio::ip::make_address_v4(host, ec);
  return !ec;
}

bool is_ipv6(const std::string& host) {
  asio::error_code ec;
  asio::ip::make_address_v6(host, ec);  // takes a zone too: fe80::1%eth0
  return !ec;
}

// The address part, checked for its use; `port` only to write the examples with.
void check_host(const std::string& host, bool bracketed, const std::string& port, PortUse use) {
  if (bracketed) {
    if (!is_ipv6(host)) {
      throw std::invalid_argument(
          fmt::format("'[{}]' is not an IPv6 address (only an IPv6 "
                      "address goes in brackets: [::1]:{})",
                      host, port));
    }
    return;
  }
  if (host.empty()) {
    throw std::invalid_argument(
        use == PortUse::kListen
            ? fmt::format("no address before the port (e.g. 127.0.0.1:{0}, or 0.0.0.0:{0} for "
                          "every interface)",
                          port)
            : std::string("no host before the port"));
  }
  // Unbracketed, "::1:10001" would read as the address ::1:10001 without a port as well.
  if (is_ipv6(host)) {
    throw std::invalid_argument(
        fmt::format("an IPv6 address goes in brackets, as in a URL: [{}]:{}", host, port));
  }
  if (host.find_first_of(": \t[]") != std::string::npos) {
    throw std::invalid_argument(fmt::format("'{}' is not a host name or address", host));
  }
  // A listening socket binds an address of this PC: a name would be looked up first.
  if (use == PortUse::kListen && !is_ipv4(host)) {
    throw std::invalid_argument(
        fmt::format("listen address '{}' is not a numeric address (e.g. "
                    "127.0.0.1, 0.0.0.0 for every interface, [::1], "
                    "[::])",
                    host));
  }
}

// Decimal digits only, leading zeros too (0080 is 80, as in a URL); 99999 wrapped round to
// 34463 once.
uint16_t port_of(const std::string& text, PortUse use) {
  const unsigned long lowest = use == PortUse::kListen ? 0 : 1;
  const size_t first = text.find_first_not_of('0');
  const std::string digits = first == std::string::npos ? "0" : text.substr(first);
  const bool decimal = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  if (!decimal || digits.size() > 5 || std::stoul(digits) > 65535 || std::stoul(digits) < lowest) {
    throw std::invalid_argument(use == PortUse::kListen
                                    ? "the port must be 0 .. 65535 (0: any free port)"
                                    : "the port must be 1 .. 65535");
  }
  return static_cast<uint16_t>(std::stoul(digits));
}

}  // namespace

HostPort parse_host_port(const std::string& text, PortUse use) {
  const bool bracketed = !text.empty() && text[0] == '[';
  const size_t close = bracketed ? text.find(']') : std::string::npos;
  if (bracketed && close == std::string::npos) {
    throw std::invalid_argument("'[' without its ']' (an IPv6 address in brackets: [::1]:10001)");
  }
  // The colon before the port: right after the ']', else the last one.
  const size_t colon = bracketed ? close + 1 : text.rfind(':');
  if (colon >= text.size() || text[colon] != ':') {
    throw std::invalid_argument(
        "expected ADDR:PORT (e.g. 127.0.0.1:10001, or [::1]:10001 for IPv6)");
  }
  HostPort hp;
  hp.host = bracketed ? text.substr(1, close - 1) : text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  check_host(hp.host, bracketed, port, use);
  hp.port = port_of(port, use);
  return hp;
}

std::string host_port_text(const std::string& host, int port) {
  const bool ipv6 = host.find(':') != std::string::npos;
  return ipv6 ? fmt::format("[{}]:{}", host, port) : fmt::format("{}:{}", host, port);
}

}  // namespace host
