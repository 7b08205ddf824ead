// The server's sockets with a bounded head (see bounded_http_server.h).
#include "host/lib/server/bounded_http_server.h"

#include <netdb.h>       // getnameinfo, NI_NUMERICHOST
#include <poll.h>        // poll
#include <sys/socket.h>  // recv, send, shutdown, getpeername, getsockname
#include <unistd.h>      // close

#include <algorithm>  // std::min
#include <cctype>     // std::tolower
#include <cerrno>     // errno, EINTR
#include <chrono>     // std::chrono::steady_clock
#include <string>     // std::string

namespace host::server {

namespace {

// Host header lines in the head this thread is reading (see host_header_lines()).
thread_local int t_host_lines = 0;

void address_of(int fd, bool peer, std::string& ip, int& port) {
  sockaddr_storage a{};
  socklen_t len = sizeof a;
  auto* sa = reinterpret_cast<sockaddr*>(&a);
  if ((peer ? ::getpeername(fd, sa, &len) : ::getsockname(fd, sa, &len)) != 0) return;
  char host[NI_MAXHOST];
  char serv[NI_MAXSERV];
  if (::getnameinfo(sa, len, host, sizeof host, serv, sizeof serv,
                    NI_NUMERICHOST | NI_NUMERICSERV) != 0)
    return;
  ip = host;
  port = std::stoi(serv);
}

// A socket whose reads stop at kHeadBytes, or past kHeadSeconds, until the blank line that
// ends the head; the body is httplib's to bound (the payload limit, the upload's count).
class HeadBoundedStream : public httplib::Stream {
 public:
  HeadBoundedStream(socket_t sock, int read_timeout_ms, int write_timeout_ms)
      : sock_(sock),
        read_ms_(read_timeout_ms),
        write_ms_(write_timeout_ms),
        head_deadline_(std::chrono::steady_clock::now() +
                       std::chrono::seconds(BoundedHttpServer::kHeadSeconds)) {
    t_host_lines = 0;
  }

  bool is_readable() const override { return wait(POLLIN, read_ms_); }
  bool is_writable() const override { return wait(POLLOUT, write_ms_); }

  ssize_t read(char* ptr, size_t size) override {
    if (!in_body_ && (head_bytes_ >= BoundedHttpServer::kHeadBytes ||
                      std::chrono::steady_clock::now() > head_deadline_))
      return -1;
    if (!in_body_) size = std::min(size, BoundedHttpServer::kHeadBytes - head_bytes_);
    if (!is_readable()) return -1;
    ssize_t n = 0;
    do {
      n = ::recv(sock_, ptr, size, 0);
    } while (n < 0 && errno == EINTR);
    if (n > 0 && !in_body_) see_head(ptr, static_cast<size_t>(n));
    return n;
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    ssize_t n = 0;
    do {
      n = ::send(sock_, ptr, size, MSG_NOSIGNAL);
    } while (n < 0 && errno == EINTR);
    return n;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address_of(sock_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address_of(sock_, false, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  bool wait(short events, int timeout_ms) const {
    pollfd p{sock_, events, 0};
    int n = 0;
    do {
      n = ::poll(&p, 1, timeout_ms);
    } while (n < 0 && errno == EINTR);
    return n > 0 && (p.revents & (events | POLLHUP | POLLERR)) != 0;
  }
  // The head ends at its first empty line (CR LF or a bare LF, as httplib reads lines).
  // Lines that begin "Host:" (any case) are counted: httplib drops one with an empty value.
  void see_head(const char* p, size_t n) {
    static const char kHost[] = "host:";
    head_bytes_ += n;
    for (size_t i = 0; i < n && !in_body_; ++i) {
      if (p[i] == '\n') {
        in_body_ = line_bytes_ == 0 && lines_ > 0;  // not before the request line
        ++lines_;
        line_bytes_ = 0;
        host_prefix_ = true;
      } else if (p[i] != '\r') {
        if (line_bytes_ < 5) {
          host_prefix_ =
              host_prefix_ && std::tolower(static_cast<unsigned char>(p[i])) == kHost[line_bytes_];
          if (line_bytes_ == 4 && host_prefix_ && lines_ > 0) ++t_host_lines;
        }
        ++line_bytes_;
      }
    }
  }

  socket_t sock_;
  int read_ms_, write_ms_;
  std::chrono::steady_clock::time_point head_deadline_;
  size_t head_bytes_ = 0;    // read before the head ended
  size_t line_bytes_ = 0;    // of the line being read, CR aside
  size_t lines_ = 0;         // ended so far
  bool host_prefix_ = true;  // the line so far is a prefix of "host:"
  bool in_body_ = false;
};

}  // namespace

int host_header_lines() {
  return t_host_lines;
}

bool BoundedHttpServer::process_and_close_socket(socket_t sock) {
  bool answered = false;
  {
    HeadBoundedStream strm(
        sock, static_cast<int>(read_timeout_sec_ * 1000 + read_timeout_usec_ / 1000),
        static_cast<int>(write_timeout_sec_ * 1000 + write_timeout_usec_ / 1000));
    bool closed = false;
    answered = process_request(strm, true, closed, nullptr);
  }
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return answered;
}

}  // namespace host::server
