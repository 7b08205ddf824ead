// Varints and zigzag (see varint.h).
#include "firmware/protocol/varint.h"

namespace proto {

uint32_t zigzag(int32_t v) {
  return v >= 0 ? (uint32_t)v << 1 : (((uint32_t)(-(v + 1))) << 1) | 1U;
}

int32_t unzigzag(uint32_t u) {
  const uint32_t half = u >> 1;
  // Odd codes are the negatives: -(half) - 1, computed without overflow.
  return (u & 1U) ? -(int32_t)half - 1 : (int32_t)half;
}

uint8_t put_varint(uint32_t v, uint8_t* out) {
  uint8_t n = 0;
  while (v >= 0x80U) {
    out[n++] = (uint8_t)((v & 0x7FU) | 0x80U);
    v >>= 7;
  }
  out[n++] = (uint8_t)v;
  return n;
}

ErrorCode VarintReader::next(uint32_t* v) {
  uint32_t value = 0;
  for (uint8_t i = 0; i < kMaxVarintBytes; ++i) {
    if (at_ >= size_) return ErrorCode::kPayloadLength;
    const uint8_t b = data_[at_++];
    if (i == kMaxVarintBytes - 1 && b > 0x0FU) return ErrorCode::kFieldRange;
    value |= (uint32_t)(b & 0x7FU) << (7U * i);
    if ((b & 0x80U) == 0) {
      *v = value;
      return ErrorCode::kOk;
    }
  }
  return ErrorCode::kFieldRange;  // not reached: the fifth byte has no continuation bit
}

}  // namespace proto
