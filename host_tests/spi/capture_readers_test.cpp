// Capture readers: VCD, Saleae CSVs, zip/.sr, and what they do with damaged input.
#include <gtest/gtest.h>

#include <cstdio>    // std::snprintf
#include <fstream>   // std::ifstream
#include <iterator>  // std::istreambuf_iterator
#include <random>    // std::mt19937

#include "host/spi/capture.h"
#include "host_tests/spi/test_util.h"
#include "host_tests/spi/vcd_synth.h"

using namespace host::spi;

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(VcdReader, ScalesTimesByTimescale) {
  std::string vcd =
      "$timescale 10 ns $end\n$scope module x $end\n$var wire 1 ! CS# $end\n$upscope $end\n"
      "$enddefinitions $end\n#0 1!\n#5 0!\n#12 1!\n";
  Trace t;
  ASSERT_TRUE(parse_vcd(vcd, &t).ok());
  ASSERT_EQ(t.channels.size(), 1u);
  EXPECT_EQ(t.channels[0].name, "CS#");
  EXPECT_TRUE(t.channels[0].initial_high);
  EXPECT_EQ(t.channels[0].toggles_ps, (std::vector<int64_t>{50000, 120000}));
  EXPECT_EQ(t.end_ps, 120000);
}

TEST(VcdReader, TimeGoingBackwardsIsAFormatError) {
  std::string vcd = "$var wire 1 ! A $end\n$enddefinitions $end\n#10 1!\n#5 0!\n";
  Trace t;
  EXPECT_EQ(parse_vcd(vcd, &t).code, "E_FORMAT");
}

TEST(VcdReader, UndeclaredIdentifierIsAFormatError) {
  std::string vcd = "$var wire 1 ! A $end\n$enddefinitions $end\n#0 1?\n#5\n";
  Trace t;
  EXPECT_EQ(parse_vcd(vcd, &t).code, "E_FORMAT");
}

TEST(VcdReader, HeaderOnlyFileIsAFormatError) {
  Trace t;
  EXPECT_EQ(parse_vcd("$timescale 1ns $end\n$var wire 1 ! A $end\n", &t).code, "E_FORMAT");
}

TEST(SaleaeDigitalCsv, TransitionsBecomeChannels) {
  std::string csv =
      "Time [s],Channel 0,Channel 1\n0.000000000,1,1\n0.000001000,0,1\n0.000001500,0,0\n";
  Trace t;
  ASSERT_TRUE(parse_saleae_digital_csv(csv, &t).ok());
  ASSERT_EQ(t.channels.size(), 2u);
  EXPECT_EQ(t.channels[1].name, "Channel 1");
  EXPECT_EQ(t.channels[0].toggles_ps, (std::vector<int64_t>{1000000}));
  EXPECT_EQ(t.channels[1].toggles_ps, (std::vector<int64_t>{1500000}));
}

TEST(SaleaeDigitalCsv, DecodesLikeTheSameVcd) {
  // A mode-3 byte 0xA5 written as a Saleae digital export with named channels.
  std::string csv = "Time [s],CS,SCK,MOSI\n0,1,1,0\n1e-6,0,1,0\n";
  auto sec = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9f", v);
    return std::string(b);
  };
  double t = 2e-6;
  for (int i = 0; i < 8; ++i) {
    int bit = (0xA5 >> (7 - i)) & 1;
    csv += sec(t) + ",0,0," + std::to_string(bit) + "\n";
    csv += sec(t + 0.5e-6) + ",0,1," + std::to_string(bit) + "\n";
    t += 1e-6;
  }
  csv += sec(t + 1e-6) + ",1,1,0\n";
  Capture cap;
  ASSERT_TRUE(load_capture_bytes(csv, "t.csv", &cap).ok());
  ASSERT_FALSE(cap.predecoded);
  FramerOptions o;
  o.bits = 8;
  FramerResult r;
  ASSERT_TRUE(frame_capture(cap.trace, o, &r).ok());
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].mosi, 0xA5u);
  EXPECT_EQ(r.frames[0].flags, 0u);
}

TEST(SaleaeSpiCsv, Logic1PacketIdGroupsBytesIntoOneDatagram) {
  std::string csv =
      "Time [s],Packet ID,MOSI,MISO\n0.0010,0,0x1A,0x15\n0.0011,0,0x00,0x00\n"
      "0.0012,0,0x01,0x00\n0.0013,0,0x23,0x00\n0.0020,1,0x7E,0x15\n0.0021,1,0x01,0x00\n"
      "0.0022,1,0x07,0x00\n0.0023,1,0x02,0x00\n";
  Capture cap;
  ASSERT_TRUE(load_capture_bytes(csv, "spi.csv", &cap).ok());
  ASSERT_TRUE(cap.predecoded);
  ASSERT_EQ(cap.frames.size(), 2u);
  EXPECT_EQ(cap.frames[0].mosi, 0x1A000123u);
  EXPECT_EQ(cap.frames[0].miso, 0x15000000u);
  EXPECT_EQ(cap.frames[0].bit_count, 32);
  EXPECT_EQ(cap.frames[1].mosi, 0x7E010702u);
}

TEST(SaleaeSpiCsv, Logic2EnableDisableRowsBoundADatagram) {
  std::string csv =
      "name,type,start_time,duration,mosi,miso\n"
      "\"SPI\",\"enable\",0.001,1e-8,,\n\"SPI\",\"result\",0.0010001,6e-6,0x1A,0x15\n"
      "\"SPI\",\"result\",0.0010071,6e-6,0x000123,0x000000\n\"SPI\",\"disable\",0.00102,1e-8,,\n";
  Capture cap;
  ASSERT_TRUE(load_capture_bytes(csv, "spi2.csv", &cap).ok());
  ASSERT_EQ(cap.frames.size(), 1u);
  EXPECT_EQ(cap.frames[0].mosi, 0x1A000123u);
  EXPECT_EQ(cap.frames[0].bit_count, 32);
}

TEST(LoadCapture, MissingFileIsEOpen) {
  Capture cap;
  EXPECT_EQ(load_capture("/nonexistent/capture.vcd", &cap).code, "E_OPEN");
}

TEST(LoadCapture, DirectoryIsEOpen) {
  Capture cap;
  EXPECT_EQ(load_capture(::testing::TempDir(), &cap).code, "E_OPEN");
}

TEST(VcdReader, FileCutInsideItsLastTokenIsReadUpToTheCut) {
  // "#1" + "5" lost: a capture tool stopped mid-write.
  std::string vcd = "$var wire 1 ! CS $end\n$enddefinitions $end\n#0 1!\n#10 0!\n#";
  Trace t;
  ASSERT_TRUE(parse_vcd(vcd, &t).ok());
  EXPECT_EQ(t.channels[0].toggles_ps, (std::vector<int64_t>{10000}));
  EXPECT_EQ(t.end_ps, 10000);
}

TEST(LoadCapture, EmptyAndUnknownInputAreEFormat) {
  Capture cap;
  EXPECT_EQ(load_capture_bytes("", "empty", &cap).code, "E_FORMAT");
  EXPECT_EQ(load_capture_bytes("hello world\n", "text", &cap).code, "E_FORMAT");
}

TEST(LoadCapture, TruncatedSigrokFileIsACodedError) {
  std::string sr = read_all(spi_test::data_path("adf4351__set-4000mhz.sr"));
  ASSERT_GT(sr.size(), 1000u);
  Capture cap;
  for (size_t keep : {size_t(4), size_t(100), sr.size() / 2, sr.size() - 1}) {
    Error e = load_capture_bytes(sr.substr(0, keep), "cut.sr", &cap);
    EXPECT_EQ(e.code, "E_FORMAT") << keep;
  }
}

TEST(LoadCapture, CorruptedSigrokDataIsACodedError) {
  std::string sr = read_all(spi_test::data_path("adf4351__set-4000mhz.sr"));
  ASSERT_GT(sr.size(), 1000u);
  for (size_t i = 200; i < 600; ++i) sr[i] = static_cast<char>(sr[i] ^ 0x5A);
  Capture cap;
  EXPECT_FALSE(load_capture_bytes(sr, "bad.sr", &cap).ok());
}

TEST(LoadCapture, RandomBytesNeverCrashAndGiveACodedError) {
  std::mt19937 rng(1234);
  for (int round = 0; round < 200; ++round) {
    std::string junk(rng() % 400, '\0');
    for (char& c : junk) c = static_cast<char>(rng());
    // Some rounds pretend to be a zip, a VCD or a CSV.
    if (round % 4 == 1) junk = "PK\x03\x04" + junk;
    if (round % 4 == 2) junk = "$var wire 1 ! A $end\n$enddefinitions $end\n#0 " + junk;
    if (round % 4 == 3) junk = "Time [s],Packet ID,MOSI,MISO\n" + junk;
    Capture cap;
    Error e = load_capture_bytes(junk, "junk", &cap);
    if (!e.ok()) EXPECT_FALSE(e.code.empty());
  }
}

TEST(LoadCapture, TruncatedVcdStillFramesWhatIsThere) {
  spi_test::Synth s;
  std::string vcd = s.vcd({{0x12345678, 0}, {0x9ABCDEF0, 0}});
  for (size_t keep = 0; keep < vcd.size(); keep += 37) {
    Capture cap;
    Error e = load_capture_bytes(vcd.substr(0, keep), "cut.vcd", &cap);
    if (!e.ok()) continue;
    FramerResult r;
    frame_capture(cap.trace, FramerOptions(), &r);  // must not crash; result may be partial
    for (const Frame& f : r.frames) EXPECT_LE(f.bit_count, 32);
  }
}

}  // namespace
