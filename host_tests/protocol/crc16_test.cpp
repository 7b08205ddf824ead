// CRC-16/IBM-3740 against its published check value.
#include "firmware/protocol/crc16.h"

#include <gtest/gtest.h>

#include <cstring>  // strlen

namespace {

TEST(Crc16, CheckValueOf123456789Is0x29B1) {
  const char* text = "123456789";
  EXPECT_EQ(0x29B1, proto::crc16(reinterpret_cast<const uint8_t*>(text), strlen(text)));
}

TEST(Crc16, EmptyInputGivesTheInitialValue) {
  EXPECT_EQ(0xFFFF, proto::crc16(nullptr, 0));
}

TEST(Crc16, ByteAtATimeEqualsWholeBuffer) {
  const uint8_t data[] = {0x23, 0x47, 0x05, 0x00, 0xFF, 0x00, 0x80};
  uint16_t crc = proto::kCrcInit;
  for (uint8_t b : data) crc = proto::crc16_update(crc, b);
  EXPECT_EQ(proto::crc16(data, sizeof data), crc);
}

// Independent value: Python's binascii.crc_hqx(b'A', 0xFFFF) == 0xB915.
TEST(Crc16, SingleByteAMatchesCatalogueValue) {
  const uint8_t a = 'A';
  EXPECT_EQ(0xB915, proto::crc16(&a, 1));
}

}  // namespace
