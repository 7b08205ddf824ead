// Variable-length integers of the compact spline frames (#K, #Q; docs/protocol.md): 7 bits
// a byte, lowest group first, bit 7 set on every byte but the last, at most 5 bytes (a fifth
// byte above 0x0F is refused); zigzag maps a signed value to them (0, -1, 1, -2 -> 0, 1, 2, 3).
#ifndef FIRMWARE_PROTOCOL_VARINT_H
#define FIRMWARE_PROTOCOL_VARINT_H

#include <stdint.h>  // uint8_t, int32_t, uint32_t

#include "firmware/protocol/wire_codes.h"  // ErrorCode

namespace proto {

enum { kMaxVarintBytes = 5 };

uint32_t zigzag(int32_t v);
int32_t unzigzag(uint32_t u);

// Bytes written to out (1..kMaxVarintBytes).
uint8_t put_varint(uint32_t v, uint8_t* out);

// Reads a frame's data one varint at a time.
class VarintReader {
 public:
  VarintReader(const uint8_t* data, uint8_t size) : data_(data), size_(size), at_(0) {}
  // kOk and *v; kPayloadLength when the data ends inside the number, kFieldRange when it
  // is longer than 32 bits.
  ErrorCode next(uint32_t* v);
  bool at_end() const { return at_ == size_; }

 private:
  const uint8_t* data_;
  uint8_t size_;
  uint8_t at_;
};

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_VARINT_H
