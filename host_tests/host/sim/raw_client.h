// A raw TCP client of the simulator's server for tests that need bytes on the wire a
// `Sender` would never write (a hang-up mid-stream, frames left unread).
#ifndef HOST_TESTS_HOST_SIM_RAW_CLIENT_H
#define HOST_TESTS_HOST_SIM_RAW_CLIENT_H

#include <gtest/gtest.h>

#include <arpa/inet.h>   // inet_pton
#include <netinet/in.h>  // sockaddr_in
#include <sys/socket.h>  // socket, connect
#include <unistd.h>      // close, write

#include <vector>  // std::vector

#include "firmware/protocol/codec.h"

namespace host::test {

// Appends message m as one frame with sequence number seq.
template <typename Msg>
void append_frame(const Msg& m, uint8_t seq, std::vector<uint8_t>* out) {
  uint8_t buf[proto::kMaxFrameBytes];
  uint8_t n = 0;
  ASSERT_EQ(proto::write_frame(m, seq, buf, sizeof buf, &n), proto::ErrorCode::kOk);
  out->insert(out->end(), buf, buf + n);
}

// A socket connected to 127.0.0.1:port; -1 when the connection failed.
inline int connect_to(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  ::inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
  if (fd >= 0 && ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// Writes every byte (a test failure when the socket takes none).
inline void write_all(int fd, const std::vector<uint8_t>& bytes) {
  size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    ASSERT_GT(n, 0);
    at += static_cast<size_t>(n);
  }
}

}  // namespace host::test

#endif  // HOST_TESTS_HOST_SIM_RAW_CLIENT_H
