// The names and addresses the server answers to in the Host header. A page on another site
// that a browser on this PC opens could otherwise read the server's jobs through a DNS name
// that resolves to this PC (DNS rebinding): the browser sends that name as Host.
#ifndef HOST_LIB_SERVER_ALLOWED_HOSTS_H
#define HOST_LIB_SERVER_ALLOWED_HOSTS_H

#include <set>     // std::set
#include <string>  // std::string
#include <vector>  // std::vector

namespace host::server {

class AllowedHosts {
 public:
  // listen_address: the address the server listens on; extra: names or addresses given
  // with --allowed-host. Always allowed: the listen address, localhost, 127.0.0.1 and
  // [::1]; listening on all addresses (0.0.0.0, ::) adds the PC's host name and the
  // addresses of its network interfaces.
  AllowedHosts(const std::string& listen_address, const std::vector<std::string>& extra);
  // The port the server listens on: a Host header that names a port must name this one
  // (or a NAME:PORT given as extra, for a proxy in front). 0: any port (not yet bound).
  void set_port(int port) { port_ = port; }
  // Whether a request with this Host header ("name", "name:port", "[v6]:port") is served.
  // Without a port (the scheme's default: a proxy in front, or the server on port 80) any
  // allowed name is.
  bool allows(const std::string& host_header) const;
  // The names, comma-separated (for the start-up message).
  std::string describe() const;

 private:
  void add(const std::string& name);
  std::set<std::string> names_;      // lower case, no port, IPv6 in brackets
  std::set<std::string> with_port_;  // extra NAME:PORT, as host_of_header + ":" + port
  int port_ = 0;
};

// The host part of a Host header in the form AllowedHosts keeps ("" when malformed).
std::string host_of_header(const std::string& host_header);
// Its port: -1 when it names none, -2 when that is not a port (1 .. 65535).
int port_of_header(const std::string& host_header);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_ALLOWED_HOSTS_H
