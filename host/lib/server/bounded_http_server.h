// cpp-httplib's server with a bound on a request's line and headers, and one request a
// connection. httplib 0.11.4 reads a request line or a header line whole before it checks
// its length (an outside tester sent a 337 MB header line, no token needed: 405 MB
// resident), and keeps a connection open after a refusal it gave from the headers alone
// (the body the client sent anyway was read as further requests).
#ifndef HOST_LIB_SERVER_BOUNDED_HTTP_SERVER_H
#define HOST_LIB_SERVER_BOUNDED_HTTP_SERVER_H

#include <httplib.h>  // httplib::Server

#include <cstddef>  // size_t

namespace host::server {

// Lines beginning "Host:" in the head of the request this thread is answering, empty ones
// included (httplib drops a header with no value: "Host:" beside "Host: 127.0.0.1" was one
// Host); 0 outside a BoundedHttpServer's request.
int host_header_lines();

class BoundedHttpServer : public httplib::Server {
 public:
  // The request line and every header together; beyond it the connection is closed.
  static constexpr size_t kHeadBytes = 64 * 1024;
  // The whole head must come within this (a client that trickles it holds a thread).
  static constexpr int kHeadSeconds = 20;

 private:
  // One request, then the connection closes (Connection: close on every answer).
  bool process_and_close_socket(socket_t sock) override;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_BOUNDED_HTTP_SERVER_H
