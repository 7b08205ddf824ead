// The SPI record file format and the recording SPI master.
#include <gtest/gtest.h>

#include <sstream>

#include "hal/fake/spi/recording_spi.h"
#include "hal/fake/spi/spi_record.h"

namespace {

TEST(SpiRecordFile, WritesTimeInMicrosecondsAndTwoHexWords) {
  std::ostringstream out;
  fake::write_spi_records(out, {{27200, 0x7E110702u, 0x15000000u}});
  EXPECT_EQ(out.str(),
            "# engraver spi record v1: time_us mosi miso\n"
            "27.200 7E110702 15000000\n");
}

TEST(SpiRecordFile, AppendsAnnotationsAsComments) {
  std::ostringstream out;
  fake::write_spi_records(out, {{0, 1u, 2u}},
                          [](const fake::SpiRecord&) { return std::string("note"); });
  EXPECT_NE(out.str().find("0.000 00000001 00000002  # note\n"), std::string::npos);
}

TEST(SpiRecordFile, ReadsBackWhatItWrote) {
  const std::vector<fake::SpiRecord> records = {{0, 0x1A000A5Au, 0x15000000u},
                                                {26800, 0x1B000000u, 0x15000A5Au},
                                                {123456789, 0xFFFFFFFFu, 0u}};
  std::stringstream file;
  fake::write_spi_records(file, records);
  std::vector<fake::SpiRecord> back;
  std::string error;
  ASSERT_TRUE(fake::read_spi_records(file, &back, &error)) << error;
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[1].time_ns, 26800u);
  EXPECT_EQ(back[1].mosi, 0x1B000000u);
  EXPECT_EQ(back[2].time_ns, 123456789u);
  EXPECT_EQ(back[2].mosi, 0xFFFFFFFFu);
}

TEST(SpiRecordFile, AcceptsWholeMicrosecondsAndLowerCaseHex) {
  std::istringstream file("12 7e110702 0000abcd\n\n   # comment only\n");
  std::vector<fake::SpiRecord> records;
  std::string error;
  ASSERT_TRUE(fake::read_spi_records(file, &records, &error)) << error;
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].time_ns, 12000u);
  EXPECT_EQ(records[0].miso, 0xABCDu);
}

TEST(SpiRecordFile, NamesTheLineOfAMalformedRecord) {
  std::istringstream file("0.000 7E110702 00000000\n1.000 7E1107 00000000\n");
  std::vector<fake::SpiRecord> records;
  std::string error;
  EXPECT_FALSE(fake::read_spi_records(file, &records, &error));
  EXPECT_EQ(error, "line 2: expected 'time_us mosi miso'");
}

TEST(SpiTiming, TwentySixPointEightMicrosecondsPerDatagramAt1250kHz) {
  const fake::SpiTiming t = fake::spi_timing(1250000, 10000000);
  EXPECT_EQ(t.sck_period_ns, 800u);
  // CS setup and hold: half a clock (400 ns) >= 3 TMC428 clocks (300 ns, Tab. 6-1).
  EXPECT_EQ(t.cs_setup_ns, 400u);
  EXPECT_EQ(t.cs_hold_ns, 400u);
  EXPECT_EQ(t.miso_delay_ns, 300u);
  // 400 + 31.5 * 800 + 400 + 800 (CS high) = 26800.
  EXPECT_EQ(t.datagram_ns(), 26800u);
}

TEST(RecordingSpi, RecordsEachTransferAndAdvancesTheDevice) {
  fake::StuckMisoDevice device(0x12345678u);
  fake::RecordingSpi spi(device, 1250000);
  EXPECT_EQ(spi.transfer32(0xAABBCCDDu), 0x12345678u);
  spi.transfer32(1);
  ASSERT_EQ(spi.records().size(), 2u);
  EXPECT_EQ(spi.records()[0].mosi, 0xAABBCCDDu);
  EXPECT_EQ(spi.records()[0].miso, 0x12345678u);
  EXPECT_EQ(spi.records()[1].time_ns, 26800u);
  EXPECT_EQ(device.now_ns(), 2 * 26800u);
}

TEST(RecordingSpi, CanLeaveTimeToTheCaller) {
  fake::StuckMisoDevice device(0);
  fake::RecordingSpi spi(device, 1250000);
  spi.set_advance_device(false);
  spi.transfer32(1);
  EXPECT_EQ(device.now_ns(), 0u);
}

}  // namespace
