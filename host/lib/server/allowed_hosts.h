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
  // Whether a request with this Host header ("name", "name:port", "[v6]:port") is served.
  bool allows(const std::string& host_header) const;
  // The names, comma-separated (for the start-up message).
  std::string describe() const;

 private:
  void add(const std::string& name);
  std::set<std::string> names_;  // lower case, no port, IPv6 in brackets
};

// The host part of a Host header in the form AllowedHosts keeps ("" when malformed).
std::string host_of_header(const std::string& host_header);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_ALLOWED_HOSTS_H
