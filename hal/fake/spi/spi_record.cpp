// SPI bus timing and the text record file (format in spi_record.h).
#include "hal/fake/spi/spi_record.h"  // declarations

#include <cinttypes>  // PRIu64
#include <cstdio>     // std::snprintf
#include <istream>    // std::istream, std::getline
#include <ostream>    // std::ostream
#include <sstream>    // std::istringstream

namespace fake {

SpiTiming spi_timing(uint32_t spi_clock_hz, uint32_t device_clock_hz) {
  SpiTiming t;
  t.sck_period_ns = spi_clock_hz ? 1000000000u / spi_clock_hz : 1000;
  const uint32_t clk_ns = device_clock_hz ? 1000000000u / device_clock_hz : 100;
  const uint32_t three_clk = 3 * clk_ns;
  const uint32_t half = t.sck_period_ns / 2;
  t.cs_setup_ns = half > three_clk ? half : three_clk;
  t.cs_hold_ns = half > three_clk ? half : three_clk;
  t.cs_high_ns = t.sck_period_ns > three_clk ? t.sck_period_ns : three_clk;
  // SDO_C changes 2.5-3.5 CLK after SCK falls; keep it before the rising edge.
  t.miso_delay_ns = three_clk < half ? three_clk : half / 2;
  return t;
}

bool write_spi_records(std::ostream& out, const std::vector<SpiRecord>& records,
                       const SpiAnnotator& annotate) {
  out << "# engraver spi record v1: time_us mosi miso\n";
  char line[64];
  for (const SpiRecord& r : records) {
    std::snprintf(line, sizeof line, "%" PRIu64 ".%03u %08X %08X", r.time_ns / 1000,
                  (unsigned)(r.time_ns % 1000), (unsigned)r.mosi, (unsigned)r.miso);
    out << line;
    if (annotate) {
      const std::string note = annotate(r);
      if (!note.empty()) out << "  # " << note;
    }
    out << '\n';
  }
  return static_cast<bool>(out);
}

// Parses "12.345" microseconds into nanoseconds.
static bool parse_time_us(const std::string& s, uint64_t* ns) {
  uint64_t whole = 0;
  uint64_t frac = 0;
  int frac_digits = 0;
  bool dot = false;
  if (s.empty()) return false;
  for (char c : s) {
    if (c == '.' && !dot) {
      dot = true;
    } else if (c >= '0' && c <= '9') {
      if (!dot) {
        if (whole > 100000000000000ull) return false;
        whole = whole * 10 + (uint64_t)(c - '0');
      } else if (frac_digits < 3) {
        frac = frac * 10 + (uint64_t)(c - '0');
        ++frac_digits;
      }
    } else {
      return false;
    }
  }
  while (frac_digits < 3) {
    frac *= 10;
    ++frac_digits;
  }
  *ns = whole * 1000 + frac;
  return true;
}

// Parses exactly 8 hex digits.
static bool parse_hex32(const std::string& s, uint32_t* v) {
  if (s.size() != 8) return false;
  uint32_t x = 0;
  for (char c : s) {
    uint32_t d;
    if (c >= '0' && c <= '9') {
      d = (uint32_t)(c - '0');
    } else if (c >= 'a' && c <= 'f') {
      d = (uint32_t)(c - 'a' + 10);
    } else if (c >= 'A' && c <= 'F') {
      d = (uint32_t)(c - 'A' + 10);
    } else {
      return false;
    }
    x = (x << 4) | d;
  }
  *v = x;
  return true;
}

bool read_spi_records(std::istream& in, std::vector<SpiRecord>* records, std::string* error) {
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::string t, mosi, miso, extra;
    if (!(fields >> t)) continue;  // blank or comment-only
    SpiRecord r;
    const bool ok = (fields >> mosi >> miso) && !(fields >> extra) &&
                    parse_time_us(t, &r.time_ns) && parse_hex32(mosi, &r.mosi) &&
                    parse_hex32(miso, &r.miso);
    if (!ok) {
      if (error) *error = "line " + std::to_string(number) + ": expected 'time_us mosi miso'";
      return false;
    }
    records->push_back(r);
  }
  return true;
}

}  // namespace fake
