// ADDR:PORT, read and written in one place for every TCP address of the tool (`sim --listen`,
// `serve --listen`, `send --to tcp://`): an IPv4 address or host name, or an IPv6 address in
// brackets as in a URL ([::1]:10001), then the port in decimal.
#ifndef HOST_LIB_STREAM_HOST_PORT_H
#define HOST_LIB_STREAM_HOST_PORT_H

#include <cstdint>  // uint16_t
#include <string>   // std::string

namespace host {

struct HostPort {
  std::string host;  // without the brackets: "::1"
  uint16_t port = 0;
};

// What the address is for: listening takes a numeric address of this PC and port 0 (any free
// port); connecting takes a host name too, and a port 1 .. 65535.
enum class PortUse { kListen, kConnect };

// Reads "ADDR:PORT" or "[IPV6]:PORT"; leading zeros of the port are decimal ones (0080 is
// 80). Throws std::invalid_argument saying what is wrong, without repeating `text` (the
// caller names the option and the text).
HostPort parse_host_port(const std::string& text, PortUse use);

// "127.0.0.1:10001", "[::1]:10001": an IPv6 address in brackets, as a URL writes it.
std::string host_port_text(const std::string& host, int port);

}  // namespace host

#endif  // HOST_LIB_STREAM_HOST_PORT_H
