// RAM tables: the sine table against its formula, the chain table against [429DS] §11.4.2.
#include <gtest/gtest.h>

#include <cmath>

#include "hal/drivers/tmc428/tmc428_regs.h"
#include "hal/drivers/tmc428/tmc428_tables.h"

namespace {

using namespace drivers::tmc428;

TEST(Tmc428Tables, SineTableIsTheRoundedQuarterSineClippedTo63) {
  for (int i = 0; i < 64; ++i) {
    const int y = std::min(63, (int)(0.5 + 64.0 * std::sin(i * M_PI / 128.0)));
    EXPECT_EQ(kSineTable[i], y) << i;
  }
}

TEST(Tmc428Tables, SineDatagramsMatchTheDataSheetListing) {
  // [429DS] §12 / tmc428.md §7: first, the one the v1.00 sheet misprints, last.
  EXPECT_EQ(write_datagram(kRamSineTable, ram_pair_data(kSineTable[0], kSineTable[1])),
            0xC0000200u);
  EXPECT_EQ(write_datagram(kRamSineTable + 30, ram_pair_data(kSineTable[30], kSineTable[31])),
            0xDE002C2Bu);
  EXPECT_EQ(write_datagram(kRamSineTable + 62, ram_pair_data(kSineTable[62], kSineTable[63])),
            0xFE003F3Fu);
}

TEST(Tmc428Tables, ChainTableIsTheDataSheetsDriver3LayoutForAllThreeDrivers) {
  // [429DS] §11.4.2 driver 3 (mixed decay from FD): 98000507 9A000304 9C000602 9E000D0F
  // A0000B0C A2002E0A; here repeated at 0x80, 0x8C and 0x98.
  const uint32_t expected[6] = {0x0507, 0x0304, 0x0602, 0x0D0F, 0x0B0C, 0x2E0A};
  for (int drv = 0; drv < 3; ++drv) {
    for (int k = 0; k < 6; ++k) {
      const int pair = drv * 6 + k;
      EXPECT_EQ(ram_pair_data(kDriverChainTable[2 * pair], kDriverChainTable[2 * pair + 1]),
                expected[k])
          << "driver " << drv << " datagram " << k;
    }
  }
}

TEST(Tmc428Tables, ChainTableEndsEachDriverWithNxMAndNowhereElse) {
  for (int i = 0; i < 36; ++i) {
    EXPECT_EQ((kDriverChainTable[i] & kSigNxM) != 0, i % 12 == 11) << i;
  }
  for (int i = 36; i < 64; ++i) EXPECT_EQ(kDriverChainTable[i], kSigOne) << i;
}

}  // namespace
