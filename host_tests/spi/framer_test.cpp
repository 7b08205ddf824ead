// SPI framing: clean datagrams decode exactly; each fault gets its own diagnostic.
#include <gtest/gtest.h>

#include "host/spi/framer.h"
#include "host_tests/spi/test_util.h"
#include "host_tests/spi/vcd_synth.h"

using namespace host::spi;
using spi_test::Synth;
using spi_test::Word;

namespace {

const std::vector<Word> kWords = {{0x80000510, 0x00000000},
                                  {0x7E010702, 0x15000000},
                                  {0x08000FFF, 0x14000000},
                                  {0x03000000, 0x15FFFF38}};

TEST(Framer, Mode3DatagramsDecodeToTheWordsSent) {
  Synth s;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));
  ASSERT_EQ(r.frames.size(), 4u);
  for (size_t i = 0; i < kWords.size(); ++i) {
    EXPECT_EQ(r.frames[i].mosi, kWords[i].mosi) << i;
    EXPECT_EQ(r.frames[i].miso, kWords[i].miso) << i;
    EXPECT_EQ(r.frames[i].bit_count, 32);
    EXPECT_EQ(r.frames[i].flags, 0u) << i;
  }
}

TEST(Framer, FrameTimesAreTheChipSelectEdges) {
  Synth s;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[1].start_ps, s.frame_start_ns[1] * 1000);
}

TEST(Framer, EveryModeDecodesWhenToldTheMode) {
  for (int mode = 0; mode < 4; ++mode) {
    Synth s;
    s.mode = mode;
    FramerOptions o;
    o.mode = mode;
    FramerResult r = spi_test::frame_vcd(s.vcd(kWords), o);
    ASSERT_EQ(r.frames.size(), 4u) << mode;
    EXPECT_EQ(r.frames[3].mosi, 0x03000000u) << mode;
    EXPECT_EQ(r.frames[3].miso, 0x15FFFF38u) << mode;
    EXPECT_EQ(r.frames[3].flags, 0u) << mode;
  }
}

TEST(Framer, DroppedClockPulseGivesWrongBitCountOnThatFrameOnly) {
  Synth s;
  s.drop_bit_frame = 1;
  s.drop_bit = 20;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[1].bit_count, 31);
  EXPECT_EQ(r.frames[1].flags, kFlagWrongBitCount);
  EXPECT_EQ(r.frames[0].flags, 0u);
  EXPECT_EQ(r.frames[2].flags, 0u);
}

TEST(Framer, ClockGlitchGivesAnExtraBitAndTheGlitchFlag) {
  Synth s;
  s.glitch_frame = 2;
  s.glitch_bit = 5;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[2].bit_count, 33);
  EXPECT_TRUE(r.frames[2].flags & kFlagGlitch);
  EXPECT_TRUE(r.frames[2].flags & kFlagWrongBitCount);
  EXPECT_EQ(r.frames[2].shortest_pulse_ps, 20000);
  EXPECT_EQ(r.frames[1].flags, 0u);
}

TEST(Framer, MinPulseZeroTurnsTheGlitchCheckOff) {
  Synth s;
  s.glitch_frame = 2;
  FramerOptions o;
  o.min_pulse_ps = 0;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords), o);
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[2].flags, kFlagWrongBitCount);
}

TEST(Framer, CaptureEndingInsideADatagramFlagsItCutAtEnd) {
  Synth s;
  s.vcd(kWords);                                       // learn the frame times
  s.cut_at_ns = s.frame_start_ns[3] + 800 + 800 * 10;  // ten bits into the last datagram
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[3].flags, kFlagCutAtEnd | kFlagWrongBitCount);
  EXPECT_LT(r.frames[3].bit_count, 32);
  EXPECT_TRUE(frame_is_partial(r.frames[3]));
}

TEST(Framer, Mode0CaptureReadAsMode3HasClockNotIdle) {
  Synth s;
  s.mode = 0;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));  // default --mode 3
  ASSERT_FALSE(r.frames.empty());
  for (const Frame& f : r.frames) EXPECT_TRUE(f.flags & kFlagClockNotIdle);
}

TEST(Framer, Mode3CaptureReadAsMode0HasClockNotIdle) {
  Synth s;
  FramerOptions o;
  o.mode = 0;
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords), o);
  ASSERT_FALSE(r.frames.empty());
  for (const Frame& f : r.frames) EXPECT_TRUE(f.flags & kFlagClockNotIdle);
}

TEST(Framer, BitsAnyTakesWhateverEachPeriodHolds) {
  Synth s;
  s.bits = 12;
  FramerOptions o;
  o.bits = 0;
  FramerResult r = spi_test::frame_vcd(s.vcd({{0xABC, 0}, {0x123, 0}}), o);
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].bit_count, 12);
  EXPECT_EQ(r.frames[0].mosi, 0xABCu);
  EXPECT_EQ(r.frames[1].flags, 0u);
}

TEST(Framer, WithoutChipSelectTheStreamIsCutIntoWords) {
  Synth s;
  s.bits = 8;
  FramerOptions o;
  o.bits = 8;
  o.names.cs = "none";
  FramerResult r = spi_test::frame_vcd(s.vcd({{0x12, 0}, {0x34, 0}, {0x56, 0}}), o);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frames[2].mosi, 0x56u);
}

TEST(Framer, ChannelsFoundByTmc428PinNames) {
  Synth s;
  s.cs_name = "nSCS_C";
  s.sck_name = "SCK_C";
  FramerResult r = spi_test::frame_vcd(s.vcd(kWords));
  EXPECT_EQ(r.frames.size(), 4u);
}

TEST(Framer, UnknownChannelNamesAreACodedError) {
  Synth s;
  s.cs_name = "ENABLE_LINE";
  Trace t;
  ASSERT_TRUE(parse_vcd(s.vcd(kWords), &t).ok());
  FramerResult r;
  Error e = frame_capture(t, FramerOptions(), &r);
  EXPECT_EQ(e.code, "E_CHANNEL");
  FramerOptions o;
  o.names.cs = "ENABLE_LINE";
  EXPECT_TRUE(frame_capture(t, o, &r).ok());
  EXPECT_EQ(r.frames.size(), 4u);
}

TEST(Framer, EdgeInTheSameInstantAsChipSelectRisingStillCounts) {
  // Hand-made VCD: 2 bits, the second rising clock edge together with CS rising.
  std::string vcd =
      "$timescale 1us $end\n$var wire 1 c CS $end\n$var wire 1 k SCK $end\n"
      "$var wire 1 o MOSI $end\n$enddefinitions $end\n#0\n1c\n1k\n0o\n"
      "#2\n0c\n#3\n0k\n1o\n#4\n1k\n#5\n0k\n#6\n1k\n1c\n#8\n";
  FramerOptions o;
  o.bits = 2;
  FramerResult r = spi_test::frame_vcd(vcd, o);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].bit_count, 2);
  EXPECT_EQ(r.frames[0].mosi, 3u);
  EXPECT_EQ(r.frames[0].flags, 0u);
}

TEST(Framer, DurationsParseWithUnits) {
  int64_t ps = 0;
  EXPECT_TRUE(parse_duration_ps("250ns", &ps));
  EXPECT_EQ(ps, 250000);
  EXPECT_TRUE(parse_duration_ps("1.5us", &ps));
  EXPECT_EQ(ps, 1500000);
  EXPECT_TRUE(parse_duration_ps("0", &ps));
  EXPECT_EQ(ps, 0);
  EXPECT_FALSE(parse_duration_ps("fast", &ps));
  EXPECT_FALSE(parse_duration_ps("5", &ps));
  // Plain decimals only, and nothing written non-zero that comes to 0 ps (glitch detection
  // off); a written zero with a unit or an exponent is still 0 (outside tester 17).
  for (const char* bad : {"0x10ns", "0x1p4ns", " 100ns", "1e-400s", "0.1ps", "nanns", "infs"})
    EXPECT_FALSE(parse_duration_ps(bad, &ps)) << bad;
  EXPECT_TRUE(parse_duration_ps("100 ns", &ps));
  EXPECT_EQ(ps, 100000);
  EXPECT_TRUE(parse_duration_ps("0ns", &ps));
  EXPECT_EQ(ps, 0);
  EXPECT_TRUE(parse_duration_ps("0.0e3us", &ps));
  EXPECT_EQ(ps, 0);
  EXPECT_TRUE(parse_duration_ps("1e2ns", &ps));
  EXPECT_EQ(ps, 100000);
}

}  // namespace
