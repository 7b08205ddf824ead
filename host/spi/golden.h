// Expected-datagram ("golden") files: one datagram per line as hex with nibble wildcards,
// an optional MISO pattern, an optional repeat range, '#' comments. See docs/bench-testing.md.
#ifndef HOST_SPI_GOLDEN_H
#define HOST_SPI_GOLDEN_H

#include <cstdint>  // uint64_t
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/spi/capture.h"  // Error

namespace host::spi {

// A word pattern: bits where mask is 1 must equal value. any = "-" (not checked at all).
struct Pattern {
  uint64_t value = 0;
  uint64_t mask = 0;
  int bits = 0;
  bool any = true;
};

struct Expected {
  Pattern mosi;
  Pattern miso;
  int min_count = 1;    // {min,max}: consecutive datagrams this line may match
  int max_count = 1;    // -1 = unbounded
  int line = 0;         // 1-based line in the file
  std::string comment;  // text after '#'
};

// "0x1A000123", "0x03xxxxxx", "0x03??????", "-"; false if malformed.
bool parse_pattern(const std::string& token, Pattern* out);
// Back to text: "0x03xxxxxx" (x for a wildcard nibble), "-" when any.
std::string pattern_text(const Pattern& p);
// True when a word of `bits` bits fits the pattern.
bool pattern_matches(const Pattern& p, uint64_t word, int bits);
// A fully specified pattern for a known word.
Pattern exact_pattern(uint64_t word, int bits);

// Parses a whole golden file. Error code E_GOLDEN names the line.
Error parse_golden(const std::string& text, std::vector<Expected>* out);
// Writes lines in the same format (columns aligned, comment kept).
std::string format_golden(const std::vector<Expected>& lines, const std::string& header);

}  // namespace host::spi

#endif  // HOST_SPI_GOLDEN_H
