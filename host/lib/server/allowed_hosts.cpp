// The server's own names and addresses (see allowed_hosts.h).
#include "host/lib/server/allowed_hosts.h"

#include <arpa/inet.h>   // inet_ntop
#include <ifaddrs.h>     // getifaddrs
#include <netinet/in.h>  // sockaddr_in, sockaddr_in6
#include <unistd.h>      // gethostname

#include "host/lib/drawing/file_text.h"  // lower_ascii

namespace host::server {

namespace {

// The addresses of this PC's network interfaces, IPv6 in brackets.
std::vector<std::string> interface_addresses() {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return out;
  for (ifaddrs* i = list; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr) continue;
    char buf[INET6_ADDRSTRLEN] = {};
    if (i->ifa_addr->sa_family == AF_INET) {
      const auto* a = reinterpret_cast<const sockaddr_in*>(i->ifa_addr);
      if (inet_ntop(AF_INET, &a->sin_addr, buf, sizeof buf)) out.push_back(buf);
    } else if (i->ifa_addr->sa_family == AF_INET6) {
      const auto* a = reinterpret_cast<const sockaddr_in6*>(i->ifa_addr);
      if (inet_ntop(AF_INET6, &a->sin6_addr, buf, sizeof buf))
        out.push_back("[" + std::string(buf) + "]");
    }
  }
  freeifaddrs(list);
  return out;
}

}  // namespace

std::string host_of_header(const std::string& host_header) {
  std::string h = lower_ascii(host_header);
  if (h.empty()) return "";
  if (h[0] == '[') {  // [v6] or [v6]:port
    const size_t close = h.find(']');
    if (close == std::string::npos) return "";
    const std::string rest = h.substr(close + 1);
    if (!rest.empty() && rest[0] != ':') return "";
    return h.substr(0, close + 1);
  }
  const size_t colon = h.find(':');
  if (colon != std::string::npos) {
    if (h.find(':', colon + 1) != std::string::npos) return "";  // bare IPv6: not a Host
    h = h.substr(0, colon);
  }
  if (!h.empty() && h.back() == '.') h.pop_back();  // "localhost." is "localhost"
  return h;
}

int port_of_header(const std::string& host_header) {
  if (host_of_header(host_header).empty()) return -2;
  const size_t close = host_header[0] == '[' ? host_header.find(']') : 0;
  const size_t colon = host_header.find(':', close);
  if (colon == std::string::npos) return -1;
  const std::string digits = host_header.substr(colon + 1);
  if (digits.empty() || digits.size() > 5 ||
      digits.find_first_not_of("0123456789") != std::string::npos) {
    return -2;
  }
  const int port = std::stoi(digits);
  return port >= 1 && port <= 65535 ? port : -2;
}

AllowedHosts::AllowedHosts(const std::string& listen_address,
                           const std::vector<std::string>& extra) {
  add("localhost");
  add("127.0.0.1");
  add("[::1]");
  const bool v6 = listen_address.find(':') != std::string::npos && listen_address[0] != '[';
  add(v6 ? "[" + listen_address + "]" : listen_address);
  if (listen_address == "0.0.0.0" || listen_address == "::" || listen_address == "[::]" ||
      listen_address.empty()) {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) == 0 && name[0] != '\0') add(name);
    for (const std::string& a : interface_addresses()) add(a);
  }
  for (const std::string& e : extra) add(e);
}

void AllowedHosts::add(const std::string& name) {
  const std::string h = host_of_header(name);
  const int port = port_of_header(name);
  if (h.empty() || port == -2) return;
  names_.insert(h);
  if (port > 0) with_port_.insert(h + ":" + std::to_string(port));
}

bool AllowedHosts::allows(const std::string& host_header) const {
  const std::string h = host_of_header(host_header);
  const int port = port_of_header(host_header);
  if (h.empty() || port == -2 || names_.count(h) == 0) return false;
  // Another port than ours reaches us only through something in between: a page on that
  // port is another origin, and must not read or steer this server.
  return port == -1 || port_ == 0 || port == port_ ||
         with_port_.count(h + ":" + std::to_string(port)) > 0;
}

std::string AllowedHosts::describe() const {
  std::string out;
  const std::string port = port_ > 0 ? ":" + std::to_string(port_) : "";
  for (const std::string& n : names_) out += (out.empty() ? "" : ", ") + n + port;
  for (const std::string& n : with_port_) out += ", " + n;
  return out;
}

}  // namespace host::server
