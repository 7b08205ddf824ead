// CRC-16/IBM-3740 over a buffer (see crc16.h).
#include "firmware/protocol/crc16.h"  // crc16_update

namespace proto {

uint16_t crc16(const uint8_t* data, size_t len) {
  uint16_t crc = kCrcInit;
  for (size_t i = 0; i < len; ++i) crc = crc16_update(crc, data[i]);
  return crc;
}

}  // namespace proto
