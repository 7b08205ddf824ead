// VCDs written by the fake SPI recorder (hal/fake/spi) decode to exactly the recorded
// datagrams, and the firmware's init diffs clean against `spi expect --scenario init`.
#include <gtest/gtest.h>

#include <cstdio>   // popen
#include <cstdlib>  // std::system
#include <fstream>  // std::ifstream
#include <sstream>  // std::ostringstream

#include "firmware/config/machine_config.h"  // config::default_machine_config
#include "hal/drivers/tmc428/tmc428.h"       // drivers::Tmc428
#include "hal/fake/motion/tmc428_model.h"    // fake::Tmc428Model
#include "hal/fake/spi/recording_spi.h"      // fake::RecordingSpi
#include "hal/fake/spi/spi_record.h"         // fake::read_spi_records
#include "hal/fake/spi/vcd_writer.h"         // fake::write_spi_vcd
#include "host/spi/commands.h"
#include "host/spi/diff.h"
#include "host/spi/golden.h"
#include "host/spi/report.h"
#include "host/spi/scenario.h"
#include "host_tests/spi/test_util.h"

using namespace host::spi;

namespace {

// The init datagrams of the firmware's TMC428 driver against the model, and their VCD.
struct RecordedInit {
  std::vector<fake::SpiRecord> records;
  std::string vcd;
  RecordedInit() {
    config::MachineConfig machine = config::default_machine_config();
    fake::Tmc428Model chip(machine.tmc428_clock_hz);
    fake::RecordingSpi spi(chip, machine.spi_clock_hz, machine.tmc428_clock_hz);
    drivers::Tmc428 driver(spi, machine);
    EXPECT_EQ(driver.init(), drivers::Tmc428InitResult::kOk);
    records = spi.records();
    std::ostringstream out;
    EXPECT_TRUE(fake::write_spi_vcd(out, records, spi.timing()));
    vcd = out.str();
  }
};

const RecordedInit& init() {
  static RecordedInit r;
  return r;
}

TEST(FakeSpiVcd, DecodesToExactlyTheRecordedDatagrams) {
  const RecordedInit& rec = init();
  ASSERT_GT(rec.records.size(), 100u);
  FramerResult r = spi_test::frame_vcd(rec.vcd);
  ASSERT_EQ(r.frames.size(), rec.records.size());
  for (size_t i = 0; i < r.frames.size(); ++i) {
    ASSERT_EQ(r.frames[i].mosi, rec.records[i].mosi) << i;
    ASSERT_EQ(r.frames[i].miso, rec.records[i].miso) << i;
    ASSERT_EQ(r.frames[i].flags, 0u) << i;
  }
}

TEST(FakeSpiVcd, FrameStartsAreTheRecordedTimes) {
  const RecordedInit& rec = init();
  FramerResult r = spi_test::frame_vcd(rec.vcd);
  ASSERT_EQ(r.frames.size(), rec.records.size());
  // The writer may delay a datagram to keep the minimum CS high time, never advance it.
  for (size_t i = 0; i < r.frames.size(); ++i)
    ASSERT_GE(r.frames[i].start_ps, static_cast<int64_t>(rec.records[i].time_ns) * 1000) << i;
}

TEST(FakeSpiVcd, InitCaptureDiffsCleanAgainstExpectInit) {
  std::ostringstream golden, err;
  ExpectOptions e;
  e.scenario = "init";
  ASSERT_EQ(run_expect(e, golden, err), kExitOk) << err.str();
  DiffOptions d;
  d.capture = spi_test::temp_file("init.vcd", init().vcd);
  d.expected = spi_test::temp_file("init.golden", golden.str());
  std::ostringstream out;
  EXPECT_EQ(run_diff(d, out, err), kExitOk) << out.str() << err.str();
  EXPECT_NE(out.str().find("MATCH:"), std::string::npos);
}

TEST(FakeSpiVcd, ChangedInitValueShowsAsTildeWithItsRegister) {
  // The same init with one written value altered, as a wrong firmware would send it.
  std::vector<fake::SpiRecord> records = init().records;
  size_t k = 0;
  while (k < records.size() && (records[k].mosi >> 24) != 0x7E) ++k;
  ASSERT_LT(k, records.size()) << "no SMGP write in init";
  records[k].mosi ^= 0x000100;  // clk2_div 7 -> 6
  std::ostringstream vcd;
  ASSERT_TRUE(fake::write_spi_vcd(vcd, records, fake::spi_timing(1250000, 10000000)));
  std::ostringstream golden, err;
  ExpectOptions e;
  ASSERT_EQ(run_expect(e, golden, err), kExitOk);
  DiffOptions d;
  d.capture = spi_test::temp_file("init_bad.vcd", vcd.str());
  d.expected = spi_test::temp_file("init2.golden", golden.str());
  std::ostringstream out;
  EXPECT_EQ(run_diff(d, out, err), kExitDiffer);
  EXPECT_NE(out.str().find("W SMGP"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("1 changed (~)"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("<> expected clk2_div=7"), std::string::npos) << out.str();
}

TEST(FakeSpiVcd, PinnedInitRecordOfTheDriverTestsFitsExpectInit) {
  // host_tests/hal/tmc428/golden/init.txt pins the driver's init; it must fit our golden.
  std::ifstream in(HAL_TMC428_GOLDEN_INIT);
  if (!in) GTEST_SKIP() << "no " << HAL_TMC428_GOLDEN_INIT;
  std::vector<fake::SpiRecord> pinned;
  std::string why;
  ASSERT_TRUE(fake::read_spi_records(in, &pinned, &why)) << why;
  std::vector<Frame> frames;
  for (const fake::SpiRecord& r : pinned) {
    Frame f;
    f.bit_count = 32;
    f.mosi = r.mosi;
    f.miso = r.miso;
    f.has_miso = true;
    frames.push_back(f);
  }
  std::ostringstream golden, err;
  ASSERT_EQ(run_expect(ExpectOptions(), golden, err), kExitOk);
  std::vector<Expected> expected;
  ASSERT_TRUE(parse_golden(golden.str(), &expected).ok());
  DiffResult d;
  ASSERT_TRUE(diff_datagrams(frames, expected, &d).ok());
  EXPECT_TRUE(d.same()) << diff_text(frames, expected, d, true);
}

TEST(FakeSpiVcd, SigrokDecodesTheSameMosiWords) {
  if (std::system("sigrok-cli --version >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "sigrok-cli not installed";
  std::string path = spi_test::temp_file("init_sigrok.vcd", init().vcd);
  FILE* p = popen(("sigrok-cli -I vcd -i " + path +
                   " -P spi:clk=SCK:mosi=MOSI:miso=MISO:cs=CS:cpol=1:cpha=1:wordsize=32"
                   " -A spi=mosi-data")
                      .c_str(),
                  "r");
  ASSERT_NE(p, nullptr);
  std::vector<uint32_t> words;
  char line[128];
  while (fgets(line, sizeof line, p))
    words.push_back(static_cast<uint32_t>(std::strtoul(line + 7, nullptr, 16)));
  pclose(p);
  const auto& rec = init().records;
  ASSERT_EQ(words.size(), rec.size());
  for (size_t i = 0; i < words.size(); ++i) ASSERT_EQ(words[i], rec[i].mosi) << i;
}

TEST(FakeSpiVcd, JogScenarioIsRecorded) {
  std::vector<Exchange> ex;
  ASSERT_TRUE(record_scenario("jog", "", &ex).ok());
  EXPECT_GT(ex.size(), 30u);
}

TEST(FakeSpiVcd, UnknownScenarioIsAScenarioError) {
  std::vector<Exchange> none;
  EXPECT_EQ(record_scenario("walk", "", &none).code, "E_SCENARIO");
}

}  // namespace
