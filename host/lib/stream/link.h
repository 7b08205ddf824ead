// A byte link to the controller: TCP (the XPort) or a serial port, behind one interface.
#ifndef HOST_LIB_STREAM_LINK_H
#define HOST_LIB_STREAM_LINK_H

#include <chrono>     // std::chrono::milliseconds
#include <cstddef>    // size_t
#include <cstdint>    // uint8_t
#include <memory>     // std::unique_ptr
#include <stdexcept>  // std::runtime_error
#include <string>     // std::string

namespace host {

// The link failed or closed. what() names the link and the cause.
class LinkError : public std::runtime_error {
 public:
  explicit LinkError(const std::string& msg) : std::runtime_error(msg) {}
};

class Link {
 public:
  virtual ~Link() = default;
  // Sends all bytes or throws LinkError.
  virtual void write(const uint8_t* data, size_t size) = 0;
  // Returns the bytes available, waiting at most `timeout` for the first; 0 on timeout.
  // Throws LinkError when the peer closed the link or it failed.
  virtual size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) = 0;
  // "tcp://127.0.0.1:10001" or "serial:/dev/ttyUSB0,115200".
  virtual std::string name() const = 0;
};

// What a --to argument names. Throws LinkError with the accepted forms on a bad spec.
struct LinkSpec {
  enum Kind { kTcp, kSerial } kind = kTcp;
  std::string host;    // kTcp
  uint16_t port = 0;   // kTcp
  std::string device;  // kSerial
  unsigned baud = 115200;
};
LinkSpec parse_link_spec(const std::string& spec);

// Opens the link (TCP connect within connect_timeout). Throws LinkError.
std::unique_ptr<Link> open_link(const LinkSpec& spec, std::chrono::milliseconds connect_timeout);

}  // namespace host

#endif  // HOST_LIB_STREAM_LINK_H
