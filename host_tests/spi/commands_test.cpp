// The spi subcommands end to end on files: outputs, verdicts and exit codes.
#include <gtest/gtest.h>

#include <sstream>  // std::ostringstream

#include "host/spi/commands.h"
#include "host_tests/spi/test_util.h"
#include "host_tests/spi/vcd_synth.h"

using namespace host::spi;
using spi_test::Synth;
using spi_test::temp_file;
using spi_test::Word;

namespace {

const std::vector<Word> kWords = {{0x80000510, 0},          {0x82000304, 0},
                                  {0x7E010702, 0x15000000}, {0x08000064, 0x15000000},
                                  {0x03000000, 0x15000123}, {0x28000F9C, 0x15000000}};
const char* kGolden =
    "# test golden\n0x80000510\n0x82000304\n0x7E010702   # SMGP\n0x08000064\n"
    "0x03000000 0xxxxxxxxx # x_actual read\n0x28000F9C\n";

struct DiffRun {
  int rc;
  std::string out, err;
};

DiffRun diff(const std::string& vcd, const std::string& golden = kGolden, FramerOptions o = {}) {
  DiffOptions d;
  d.capture = temp_file("cap.vcd", vcd);
  d.expected = temp_file("exp.txt", golden);
  d.framer = o;
  std::ostringstream out, err;
  int rc = run_diff(d, out, err);
  return {rc, out.str(), err.str()};
}

TEST(SpiDiff, CleanCaptureMatchesWithExitZero) {
  Synth s;
  DiffRun r = diff(s.vcd(kWords));
  EXPECT_EQ(r.rc, kExitOk) << r.out << r.err;
  EXPECT_NE(r.out.find("MATCH:"), std::string::npos);
}

TEST(SpiDiff, DroppedBitShowsTildeOnThatDatagramAndExitOne) {
  Synth s;
  s.drop_bit_frame = 3;
  s.drop_bit = 25;
  DiffRun r = diff(s.vcd(kWords));
  EXPECT_EQ(r.rc, kExitDiffer) << r.out;
  EXPECT_NE(r.out.find("~ "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrong-bit-count"), std::string::npos);
  EXPECT_NE(r.out.find("1 changed (~)"), std::string::npos) << r.out;
}

TEST(SpiDiff, GlitchIsNamedInTheDiff) {
  Synth s;
  s.glitch_frame = 2;
  DiffRun r = diff(s.vcd(kWords));
  EXPECT_EQ(r.rc, kExitDiffer);
  EXPECT_NE(r.out.find("glitch"), std::string::npos) << r.out;
}

TEST(SpiDiff, TruncatedLastDatagramIsLeftOutAndReportedMissing) {
  Synth s;
  s.vcd(kWords);
  s.cut_at_ns = s.frame_start_ns[5] + 5000;
  DiffRun r = diff(s.vcd(kWords));
  EXPECT_EQ(r.rc, kExitDiffer);
  EXPECT_NE(r.out.find("cut by the capture window left out"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 missing (-)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n- "), std::string::npos);
}

TEST(SpiDiff, SwappedMosiMisoGivesTheSwapHint) {
  Synth s;
  s.swap_data_names = true;
  DiffRun r = diff(s.vcd(kWords));
  EXPECT_EQ(r.rc, kExitDiffer);
  EXPECT_NE(r.out.find("MOSI and MISO look swapped"), std::string::npos) << r.out;
}

TEST(SpiDiff, WrongModeMakesTheCaptureUnusable) {
  Synth s;
  s.mode = 0;
  DiffRun r = diff(s.vcd(kWords));
  EXPECT_EQ(r.rc, kExitUnusable);
  EXPECT_NE(r.err.find("E_FRAME_ERRORS"), std::string::npos) << r.err;
}

TEST(SpiDiff, UnreadableCaptureIsExitTwo) {
  DiffRun r = diff("this is not a capture\n");
  EXPECT_EQ(r.rc, kExitUnusable);
  EXPECT_NE(r.err.find("E_FORMAT"), std::string::npos);
}

TEST(SpiDiff, CaptureWithoutDatagramsIsExitTwo) {
  std::string vcd =
      "$var wire 1 c CS $end\n$var wire 1 k SCK $end\n$var wire 1 o MOSI $end\n"
      "$enddefinitions $end\n#0 1c 1k 0o\n#100\n";
  DiffRun r = diff(vcd);
  EXPECT_EQ(r.rc, kExitUnusable);
  EXPECT_NE(r.err.find("E_NO_FRAMES"), std::string::npos);
}

TEST(SpiDiff, BadGoldenIsExitTwo) {
  Synth s;
  DiffRun r = diff(s.vcd(kWords), "0xZZ\n");
  EXPECT_EQ(r.rc, kExitUnusable);
  EXPECT_NE(r.err.find("E_GOLDEN"), std::string::npos);
}

TEST(SpiDiff, JsonHasStableKeys) {
  Synth s;
  DiffOptions d;
  d.capture = temp_file("cap.vcd", s.vcd(kWords));
  d.expected = temp_file("exp.txt", kGolden);
  d.json = true;
  std::ostringstream out, err;
  EXPECT_EQ(run_diff(d, out, err), kExitOk);
  auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["match"], true);
  EXPECT_EQ(j["counts"]["equal"], 6);
  EXPECT_EQ(j["steps"][2]["mark"], "=");
  EXPECT_EQ(j["steps"][2]["mosi"], "0x7E010702");
}

TEST(SpiDecode, TextShowsRegisterFieldsAndStatus) {
  Synth s;
  DecodeOptions o;
  o.capture = temp_file("dec.vcd", s.vcd(kWords));
  std::ostringstream out, err;
  EXPECT_EQ(run_decode(o, out, err), kExitOk);
  EXPECT_NE(out.str().find("W SMGP lsmd=2"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("R M1.x_actual x=291 [xEQt3 xEQt2 xEQt1]"), std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("W M2.v_target v=-100"), std::string::npos) << out.str();
}

TEST(SpiDecode, JsonFramesCarryRegisterAndFlags) {
  Synth s;
  s.drop_bit_frame = 0;
  DecodeOptions o;
  o.capture = temp_file("dec2.vcd", s.vcd(kWords));
  o.json = true;
  std::ostringstream out, err;
  EXPECT_EQ(run_decode(o, out, err), kExitDiffer);
  auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["frames"][0]["flags"][0], "wrong-bit-count");
  EXPECT_EQ(j["frames"][2]["register"], "SMGP");
  EXPECT_EQ(j["frames"][2]["fields"]["clk2_div"], 7);
  EXPECT_EQ(j["frames"][4]["status"]["byte"], "0x15");
  EXPECT_EQ(j["summary"]["errors"], 1);
}

}  // namespace
