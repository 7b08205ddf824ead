// CRC-16/IBM-3740 (a.k.a. CRC-16/CCITT-FALSE) over frame bytes: poly 0x1021, init 0xFFFF,
// no reflection, no final xor; check value for "123456789" is 0x29B1.
#ifndef FIRMWARE_PROTOCOL_CRC16_H
#define FIRMWARE_PROTOCOL_CRC16_H

#include <stddef.h>  // size_t
#include <stdint.h>  // uint16_t

namespace proto {

static const uint16_t kCrcInit = 0xFFFFU;

// Folds one byte into a running CRC (table-free, a few shifts per byte).
inline uint16_t crc16_update(uint16_t crc, uint8_t byte) {
  uint8_t x = (uint8_t)((crc >> 8) ^ byte);
  x = (uint8_t)(x ^ (x >> 4));
  return (uint16_t)((uint16_t)(crc << 8) ^ (uint16_t)((uint16_t)x << 12) ^
                    (uint16_t)((uint16_t)x << 5) ^ (uint16_t)x);
}

// CRC of a whole buffer, starting from kCrcInit.
uint16_t crc16(const uint8_t* data, size_t len);

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_CRC16_H
