// One recorded SPI datagram, bus timing, and the text record file format.
//
// Record file (text, one datagram per line, '#' starts a comment anywhere on a line):
//     # engraver spi record v1: time_us mosi miso
//     27.200 7E110702 00000000   # optional annotation
//   time_us: chip-select falling edge in microseconds, decimal with 3 fraction digits
//            (nanosecond resolution); mosi, miso: the 32-bit datagram, 8 hex digits, MSB
//            first (bit 31 is the first bit on the wire). Blank lines are ignored.
#ifndef HAL_FAKE_SPI_SPI_RECORD_H
#define HAL_FAKE_SPI_SPI_RECORD_H

#include <cstdint>     // uint32_t
#include <functional>  // std::function
#include <iosfwd>      // std::istream, std::ostream
#include <string>      // std::string
#include <vector>      // std::vector

namespace fake {

struct SpiRecord {
  uint64_t time_ns;  // chip select falls
  uint32_t mosi;
  uint32_t miso;
};

// Bus timing of one datagram (SPI mode 3, 32 bits), nanoseconds.
struct SpiTiming {
  uint32_t sck_period_ns;  // 1 / SPI clock
  uint32_t cs_setup_ns;    // CS low -> first SCK falling edge (>= 3 CLK, Tab. 6-1)
  uint32_t cs_hold_ns;     // last SCK rising edge -> CS high (>= 3 CLK)
  uint32_t cs_high_ns;     // CS high between datagrams (>= 3 CLK)
  uint32_t miso_delay_ns;  // SDO_C change after SCK falls (2.5-3.5 CLK)
  // CS low time plus the minimum high time: the datagram period.
  uint64_t datagram_ns() const {
    return (uint64_t)cs_setup_ns + 32ull * sck_period_ns - sck_period_ns / 2 + cs_hold_ns +
           cs_high_ns;
  }
};

// Timing for an SPI clock and the slave's clock (TMC428 minimums are 3 of its clocks).
SpiTiming spi_timing(uint32_t spi_clock_hz, uint32_t device_clock_hz);

// Annotation for a record line ("" = none), e.g. fake::describe_tmc428_datagram.
typedef std::function<std::string(const SpiRecord&)> SpiAnnotator;

// Writes the record file; returns false on a stream error.
bool write_spi_records(std::ostream& out, const std::vector<SpiRecord>& records,
                       const SpiAnnotator& annotate = SpiAnnotator());

// Reads a record file; on a malformed line returns false and sets *error to
// "line N: what".
bool read_spi_records(std::istream& in, std::vector<SpiRecord>* records, std::string* error);

}  // namespace fake

#endif  // HAL_FAKE_SPI_SPI_RECORD_H
