// Text and JSON renderings of decoded captures and of diffs.
#ifndef HOST_SPI_REPORT_H
#define HOST_SPI_REPORT_H

#include <nlohmann/json.hpp>  // nlohmann::json
#include <string>             // std::string
#include <vector>             // std::vector

#include "host/spi/diff.h"    // DiffResult
#include "host/spi/framer.h"  // FramerResult
#include "host/spi/golden.h"  // Expected

namespace host::spi {

// What was decoded, for the header line and JSON summary.
struct DecodeInfo {
  std::string source;  // file name
  std::string format;  // vcd, sigrok, saleae-csv, saleae-spi-csv
  int mode = 3;
  int bits = 32;
  std::vector<std::string> channel_names;  // cs, sck, mosi, miso ("-" when none)
  int empty_periods = 0;
  int64_t min_pulse_ps = 0;
};

// "0x1A000123" with (bits+3)/4 digits.
std::string hex_word(uint64_t v, int bits);
// Microseconds with 3 decimals: "12.345".
std::string time_us(int64_t ps);
// One-line description of a datagram: "W M1.v_target v=-100  [INT xEQt1]".
std::string describe_tmc428(const Frame& f);

// Human-readable decode; raw = hex words only (non-TMC captures).
std::string decode_text(const DecodeInfo& info, const std::vector<Frame>& frames, bool raw);
// Machine-readable decode with stable keys (see docs/bench-testing.md).
nlohmann::json decode_json(const DecodeInfo& info, const std::vector<Frame>& frames, bool raw);

// Diff listing with marks and register names (names = false for non-TMC words).
std::string diff_text(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                      const DiffResult& d, bool names);
// One-line verdict: "MATCH: ..." or "DIFFER: ...".
std::string diff_verdict(const DiffResult& d, size_t frames, size_t expected);
nlohmann::json diff_json(const std::vector<Frame>& frames, const std::vector<Expected>& expected,
                         const DiffResult& d);

}  // namespace host::spi

#endif  // HOST_SPI_REPORT_H
