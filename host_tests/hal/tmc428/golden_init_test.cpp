// The recorded init sequence (driver against the model) is pinned by golden/init.txt.
// A change to the sequence is deliberate: regenerate and review the diff with
//   ENGRAVER_UPDATE_GOLDEN=1 build/<dir>/host_tests/hal/tmc428/tmc428_tests \
//     --gtest_filter='Tmc428Golden.*'
//   git diff host_tests/hal/tmc428/golden/init.txt
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "firmware/config/machine_config.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/fake/motion/tmc428_describe.h"
#include "hal/fake/motion/tmc428_model.h"
#include "hal/fake/spi/recording_spi.h"
#include "hal/fake/spi/spi_record.h"

namespace {

const char kGoldenPath[] = TMC428_GOLDEN_DIR "/init.txt";

// The init sequence as a record file with datagram names.
std::string recorded_init() {
  const config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  fake::RecordingSpi spi(chip, cfg.spi_clock_hz);
  drivers::Tmc428 driver(spi, cfg);
  EXPECT_EQ(driver.init(), drivers::Tmc428InitResult::kOk);
  std::ostringstream out;
  out << "# golden: drivers::Tmc428::init() against fake::Tmc428Model, default machine\n"
         "# config. Regenerate: ENGRAVER_UPDATE_GOLDEN=1 tmc428_tests "
         "--gtest_filter='Tmc428Golden.*'\n";
  fake::write_spi_records(out, spi.records(), fake::describe_tmc428_datagram);
  return out.str();
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

// First differences, line by line, for a readable failure.
std::string line_diff(const std::string& expected, const std::string& actual) {
  const std::vector<std::string> e = split_lines(expected);
  const std::vector<std::string> a = split_lines(actual);
  std::ostringstream out;
  out << "golden " << e.size() << " lines, recorded " << a.size() << " lines\n";
  int shown = 0;
  for (size_t i = 0; i < std::max(e.size(), a.size()) && shown < 12; ++i) {
    const std::string el = i < e.size() ? e[i] : "<none>";
    const std::string al = i < a.size() ? a[i] : "<none>";
    if (el == al) continue;
    out << "line " << i + 1 << ":\n  golden:   " << el << "\n  recorded: " << al << "\n";
    ++shown;
  }
  return out.str();
}

TEST(Tmc428Golden, InitSequenceMatchesTheGoldenFile) {
  const std::string actual = recorded_init();
  const char* update = std::getenv("ENGRAVER_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    std::ofstream out(kGoldenPath);
    out << actual;
    ASSERT_TRUE(out.good()) << "cannot write " << kGoldenPath;
    GTEST_SKIP() << "regenerated " << kGoldenPath << "; review it with git diff";
  }
  std::ifstream in(kGoldenPath);
  ASSERT_TRUE(in.good()) << "missing " << kGoldenPath
                         << " (generate it with ENGRAVER_UPDATE_GOLDEN=1)";
  std::stringstream expected;
  expected << in.rdbuf();
  EXPECT_TRUE(expected.str() == actual)
      << "init sequence differs from the golden file " << kGoldenPath << "\n"
      << line_diff(expected.str(), actual)
      << "If the change is intended: ENGRAVER_UPDATE_GOLDEN=1 tmc428_tests "
         "--gtest_filter='Tmc428Golden.*' and review git diff.";
}

TEST(Tmc428Golden, GoldenFileParsesAsARecordFile) {
  std::ifstream in(kGoldenPath);
  ASSERT_TRUE(in.good());
  std::vector<fake::SpiRecord> records;
  std::string error;
  ASSERT_TRUE(fake::read_spi_records(in, &records, &error)) << error;
  ASSERT_FALSE(records.empty());
  // The sequence opens with the presence probe: write 0xA5A to M1 dx_ref_tolerance.
  EXPECT_EQ(records[0].mosi, 0x1A000A5Au);
}

}  // namespace
