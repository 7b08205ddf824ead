// Start-up LCD messages: what the operator reads after power-up (docs/flashing.md).
#include "hal/dspic30f6014/startup_messages.h"

#include <gtest/gtest.h>

#include <cstring>

#include "hal/dspic30f6014/interrupts.h"

namespace {

const uint16_t kPor = 0x0001, kBor = 0x0002, kWdto = 0x0010, kExtr = 0x0080, kTrapr = 0x8000;

TEST(StartupLine, PowerOnShowsTheBanner) {
  EXPECT_STREQ(dspic::startup_line(dspic::kTrapNone, kPor | kBor), "ENGRAVER 0.1");
}

TEST(StartupLine, ResetButtonShowsTheBanner) {
  EXPECT_STREQ(dspic::startup_line(dspic::kTrapNone, kExtr), "ENGRAVER 0.1");
}

TEST(StartupLine, RecordedTrapIsNamed) {
  EXPECT_STREQ(dspic::startup_line(dspic::kTrapAddressError, kTrapr), "RESET: ADDR TRAP");
  EXPECT_STREQ(dspic::startup_line(dspic::kTrapStackError, kTrapr), "RESET: STACK");
}

TEST(StartupLine, WatchdogAndBrownOutAreNamed) {
  EXPECT_STREQ(dspic::startup_line(dspic::kTrapNone, kWdto), "RESET: WATCHDOG");
  EXPECT_STREQ(dspic::startup_line(dspic::kTrapNone, kBor), "RESET: BROWNOUT");
}

TEST(Tmc428Line, NamesEachInitResult) {
  EXPECT_STREQ(dspic::tmc428_line(0), "TMC428 OK");
  EXPECT_STREQ(dspic::tmc428_line(2), "TMC428 E2 NO ANS");
  EXPECT_STREQ(dspic::tmc428_line(6), "TMC428 E6 DRIVER");
  EXPECT_STREQ(dspic::tmc428_line(dspic::kSpiClockFailed), "SPI CLOCK ERROR");
  EXPECT_STREQ(dspic::tmc428_line(42), "TMC428 E? UNKNWN");
}

TEST(StartupMessages, EveryMessageFitsOneRow) {
  for (int code = 0; code < 256; ++code)
    EXPECT_LE(std::strlen(dspic::tmc428_line((uint8_t)code)), 16u) << code;
  for (int trap = 0; trap < 6; ++trap)
    for (uint16_t rcon : {kPor, kBor, kWdto, kExtr, kTrapr})
      EXPECT_LE(std::strlen(dspic::startup_line((uint8_t)trap, rcon)), 16u);
}

}  // namespace
