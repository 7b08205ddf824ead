// The VCD written from recorded datagrams decodes, with sigrok's SPI decoder in mode 3 and
// 32-bit words, back to the recorded MOSI and MISO words.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "firmware/config/machine_config.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/fake/motion/tmc428_model.h"
#include "hal/fake/spi/recording_spi.h"
#include "hal/fake/spi/vcd_writer.h"

namespace {

std::vector<fake::SpiRecord> init_records(fake::SpiTiming* timing) {
  const config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  fake::RecordingSpi spi(chip, cfg.spi_clock_hz);
  drivers::Tmc428 driver(spi, cfg);
  EXPECT_EQ(driver.init(), drivers::Tmc428InitResult::kOk);
  *timing = spi.timing();
  return spi.records();
}

// Runs a shell command, returns its standard output.
std::string run(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) return out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

// The 32-bit words of "spi-1: 1A000A5A" lines.
std::vector<uint32_t> words(const std::string& text) {
  std::vector<uint32_t> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t colon = line.find(": ");
    if (colon == std::string::npos) continue;
    out.push_back((uint32_t)std::stoul(line.substr(colon + 2), nullptr, 16));
  }
  return out;
}

std::string sigrok(const std::string& vcd, const char* annotation) {
  return run("sigrok-cli -I vcd -i '" + vcd +
             "' -P spi:clk=SCK:mosi=MOSI:miso=MISO:cs=CS:cpol=1:cpha=1:wordsize=32 -A spi=" +
             annotation + " 2>&1");
}

TEST(SpiVcd, SigrokDecodesTheInitSequenceToTheRecordedDatagrams) {
  if (std::system("command -v sigrok-cli > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "sigrok-cli not installed";
  }
  fake::SpiTiming timing;
  const std::vector<fake::SpiRecord> records = init_records(&timing);
  const std::string path = testing::TempDir() + "tmc428_init.vcd";
  {
    std::ofstream out(path);
    ASSERT_TRUE(fake::write_spi_vcd(out, records, timing));
  }
  const std::vector<uint32_t> mosi = words(sigrok(path, "mosi-data"));
  const std::vector<uint32_t> miso = words(sigrok(path, "miso-data"));
  ASSERT_EQ(mosi.size(), records.size());
  ASSERT_EQ(miso.size(), records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    EXPECT_EQ(mosi[i], records[i].mosi) << "datagram " << i;
    EXPECT_EQ(miso[i], records[i].miso) << "datagram " << i;
  }
  std::remove(path.c_str());
}

// Without sigrok: sample MOSI on every SCK rising edge while CS is low.
TEST(SpiVcd, MosiSampledOnRisingEdgesWhileCsIsLowGivesTheWordMsbFirst) {
  const fake::SpiTiming timing = fake::spi_timing(1250000, 10000000);
  std::ostringstream out;
  fake::write_spi_vcd(out, {{0, 0x80000001u, 0u}}, timing);
  std::istringstream in(out.str());
  std::string line;
  std::map<char, int> level = {{'!', 1}, {'"', 1}, {'#', 0}, {'$', 0}};
  uint32_t word = 0;
  int bits = 0;
  bool body = false;
  while (std::getline(in, line)) {
    if (line == "$enddefinitions $end") body = true;
    if (!body || line.size() != 2 || (line[0] != '0' && line[0] != '1')) continue;
    const int v = line[0] - '0';
    if (line[1] == '"' && v == 1 && level['"'] == 0 && level['!'] == 0) {
      word = (word << 1) | (uint32_t)level['#'];
      ++bits;
    }
    level[line[1]] = v;
  }
  EXPECT_EQ(bits, 32);
  EXPECT_EQ(word, 0x80000001u);
}

TEST(SpiVcd, DatagramsRecordedCloserThanTheBusAllowsAreSpacedOut) {
  const fake::SpiTiming timing = fake::spi_timing(1250000, 10000000);
  std::ostringstream out;
  fake::write_spi_vcd(out, {{0, 1u, 0u}, {0, 2u, 0u}}, timing);
  // Second CS fall at 1 us lead-in + one datagram period (26.8 us).
  EXPECT_NE(out.str().find("#27800\n0!\n"), std::string::npos);
}

}  // namespace
