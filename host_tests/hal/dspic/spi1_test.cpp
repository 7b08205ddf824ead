// SPI1 for the TMC428: mode 3, 16-bit words, SCK <= 1.25 MHz, datagram framing by chip select.
#include "hal/dspic30f6014/spi1.h"

#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

// SCK from SPI1CON as the FRM defines it: Fcy / (primary * secondary).
double sck_from_spi1con(uint16_t con) {
  const int primary[4] = {64, 16, 4, 1};
  const int secondary = 8 - ((con >> 2) & 7);
  return 20e6 / (primary[con & 3] * secondary);
}

class Spi1Test : public FakeSfrTest {
 protected:
  Spi1Test() {
    sfr.poke(kLATB, 0x0004);  // chip select idles high (init_ports)
    ok = spi.init(1250000);
  }
  dspic::Spi1 spi;
  bool ok;
};

TEST_F(Spi1Test, InitSelectsMode3Master16Bit) {
  ASSERT_TRUE(ok);
  EXPECT_EQ(field(kSPI1CON, 6, 1), 1u);    // CKP = 1: clock idles high
  EXPECT_EQ(field(kSPI1CON, 8, 1), 0u);    // CKE = 0: output changes idle -> active
  EXPECT_EQ(field(kSPI1CON, 9, 1), 0u);    // SMP = 0: sample mid-bit
  EXPECT_EQ(field(kSPI1CON, 5, 1), 1u);    // MSTEN
  EXPECT_EQ(field(kSPI1CON, 10, 1), 1u);   // MODE16
  EXPECT_EQ(field(kSPI1CON, 7, 1), 0u);    // SSEN = 0: chip select by GPIO
  EXPECT_EQ(field(kSPI1CON, 14, 1), 0u);   // no framed mode
  EXPECT_EQ(field(kSPI1STAT, 15, 1), 1u);  // SPIEN
}

TEST_F(Spi1Test, InitClocksAt1_25MHzForA10MHzTmc428) {
  EXPECT_DOUBLE_EQ(sck_from_spi1con(sfr.peek(kSPI1CON)), 1.25e6);
}

TEST_F(Spi1Test, ModeIsSetWhileTheModuleIsOff) {
  // MODE16 may only change with SPIEN = 0: SPI1STAT must be 0 when SPI1CON is written.
  bool stat_off_when_con_written = false;
  uint16_t stat = 0xFFFF;
  for (const auto& w : sfr.writes()) {
    if (w.address == kSPI1STAT) stat = w.value;
    if (w.address == kSPI1CON) stat_off_when_con_written = (stat & 0x8000) == 0;
  }
  EXPECT_TRUE(stat_off_when_con_written);
}

TEST_F(Spi1Test, PrescaleGivesTheFastestClockNotAboveTheLimit) {
  EXPECT_DOUBLE_EQ(sck_from_spi1con(dspic::Spi1::prescale_bits(20000000, 1000000)), 1.0e6);
  EXPECT_NEAR(sck_from_spi1con(dspic::Spi1::prescale_bits(20000000, 2000000)), 1.6667e6, 1e2);
  EXPECT_DOUBLE_EQ(sck_from_spi1con(dspic::Spi1::prescale_bits(20000000, 2500000)), 2.5e6);
  EXPECT_DOUBLE_EQ(sck_from_spi1con(dspic::Spi1::prescale_bits(20000000, 1249999)), 1.0e6);
}

TEST_F(Spi1Test, PrescaleNeverPicksOneToOne) {
  EXPECT_DOUBLE_EQ(sck_from_spi1con(dspic::Spi1::prescale_bits(20000000, 30000000)), 10e6);
}

// The settings in the order prescale_bits prefers them, each checked by its own SCK (the
// search as it was before one division replaced one per setting).
uint16_t prescale_by_search(uint32_t fcy_hz, uint32_t max_sck_hz) {
  const uint16_t primary[4] = {64, 16, 4, 1};
  uint16_t best = dspic::Spi1::kNoPrescale;
  uint16_t best_divider = 0xFFFF;
  for (int ppre = 3; ppre >= 0; --ppre) {
    for (int spre = 7; spre >= 0; --spre) {
      const uint16_t divider = (uint16_t)(primary[ppre] * (8 - spre));
      if (divider == 1) continue;
      const uint32_t sck_ceiling = (fcy_hz + divider - 1u) / divider;
      if (sck_ceiling > max_sck_hz || divider >= best_divider) continue;
      best_divider = divider;
      best = (uint16_t)(ppre | (spre << 2));
    }
  }
  return best;
}

TEST_F(Spi1Test, PrescaleIsTheSearchOverEverySetting) {
  const uint32_t edges[] = {0u, 1u, 2u, 39062u, 39063u, 1250000u, 10000000u, 0xFFFFFFFFu};
  for (uint32_t fcy : {0u, 1u, 20000000u, 0xFFFFF000u})
    for (uint32_t sck : edges)
      EXPECT_EQ(dspic::Spi1::prescale_bits(fcy, sck), prescale_by_search(fcy, sck))
          << fcy << " " << sck;
  uint32_t x = 12345u;  // xorshift: the same inputs every run
  for (int i = 0; i < 200000; ++i) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    const uint32_t fcy = x % 400000000u;
    const uint32_t sck = x >> (i % 32);
    ASSERT_EQ(dspic::Spi1::prescale_bits(fcy, sck), prescale_by_search(fcy, sck))
        << fcy << " " << sck;
  }
}

TEST_F(Spi1Test, InitRefusesAClockSlowerThanTheLargestDivider) {
  dspic::Spi1 slow;
  EXPECT_EQ(dspic::Spi1::prescale_bits(20000000, 30000), dspic::Spi1::kNoPrescale);
  EXPECT_FALSE(slow.init(30000));
  EXPECT_EQ(field(kSPI1STAT, 15, 1), 0u);
}

TEST_F(Spi1Test, Transfer32SendsTheHighWordFirstWithChipSelectLow) {
  spi.transfer32(0x1A000123);
  ASSERT_EQ(sfr.spi1_words().size(), 2u);
  EXPECT_EQ(sfr.spi1_words()[0].mosi, 0x1A00);
  EXPECT_EQ(sfr.spi1_words()[1].mosi, 0x0123);
  EXPECT_TRUE(sfr.spi1_words()[0].cs_low);
  EXPECT_TRUE(sfr.spi1_words()[1].cs_low);
}

TEST_F(Spi1Test, Transfer32ReleasesChipSelectAfterwards) {
  spi.transfer32(0x12345678);
  EXPECT_EQ(field(kLATB, 2, 1), 1u);
}

TEST_F(Spi1Test, ChipSelectFramesEachDatagram) {
  spi.transfer32(0x11112222);
  spi.transfer32(0x33334444);
  // LATB writes: low, high, low, high around the SPI1BUF writes.
  std::string trace;
  for (const auto& w : sfr.writes()) {
    if (w.address == kLATB) trace += (w.value & 0x0004) ? 'H' : 'L';
    if (w.address == kSPI1BUF) trace += 'w';
  }
  EXPECT_EQ(trace, "LwwHLwwH");
}

TEST_F(Spi1Test, ChipSelectTimesCoverThreeTmc428Clocks) {
  // 3 CLK at 10 MHz = 300 ns = 6 Tcy setup, hold and high time: 3 waits per datagram.
  spi.transfer32(0);
  EXPECT_GE(sfr.delay_cycles(), 3u * 6u);
}

TEST_F(Spi1Test, Transfer32ReturnsTheTwoMisoWordsHighFirst) {
  sfr.spi1_queue_miso(0x15AB);
  sfr.spi1_queue_miso(0xCDEF);
  EXPECT_EQ(spi.transfer32(0x01000000), 0x15ABCDEFu);
}

TEST_F(Spi1Test, StalledBusTimesOutInsteadOfHanging) {
  sfr.set_spi1_stalled(true);
  EXPECT_EQ(spi.transfer32(0x01000000), dspic::Spi1::kTimeoutAnswer);
  EXPECT_EQ(spi.timeouts(), 1);
  EXPECT_EQ(field(kLATB, 2, 1), 1u);  // chip select released anyway
}

TEST_F(Spi1Test, StaleReceiveWordIsDiscardedBeforeADatagram) {
  sfr.poke(kSPI1STAT, sfr.peek(kSPI1STAT) | 0x0001 | 0x0040);  // SPIRBF and SPIROV left set
  sfr.spi1_queue_miso(0xAAAA);
  sfr.spi1_queue_miso(0xBBBB);
  EXPECT_EQ(spi.transfer32(0), 0xAAAABBBBu);
  EXPECT_EQ(field(kSPI1STAT, 6, 1), 0u);
}

}  // namespace
