// One SPI datagram as framed from a capture (one chip-select period), with its diagnostics.
#ifndef HOST_SPI_FRAME_H
#define HOST_SPI_FRAME_H

#include <cstdint>  // uint64_t, int64_t
#include <string>   // std::string
#include <vector>   // std::vector

namespace host::spi {

// Diagnostics on a frame; several may be set.
enum FrameFlag : uint32_t {
  kFlagWrongBitCount = 1u << 0,  // bit count differs from --bits
  kFlagCutAtStart = 1u << 1,     // chip-select was already active when the capture began
  kFlagCutAtEnd = 1u << 2,       // chip-select still active when the capture ended
  kFlagClockNotIdle = 1u << 3,   // clock not at its idle level when chip-select fell (mode)
  kFlagGlitch = 1u << 4,         // a clock or chip-select pulse shorter than --min-pulse
  kFlagTooLong = 1u << 5,        // more than 64 bits: only the last 64 are kept
};

struct Frame {
  int64_t start_ps = 0;  // chip-select falling (or window start)
  int64_t end_ps = 0;    // chip-select rising (or window end)
  int bit_count = 0;
  uint64_t mosi = 0;  // MSB first, right-aligned in bit_count bits
  uint64_t miso = 0;
  bool has_mosi = true;
  bool has_miso = false;
  uint32_t flags = 0;
  int64_t shortest_pulse_ps = 0;  // for the glitch message
};

// Names of the flags set, e.g. "wrong-bit-count,cut-at-end" (stable, used in --json).
std::vector<std::string> flag_names(uint32_t flags);

// A frame whose bits are not a complete, clean datagram.
inline bool frame_is_error(const Frame& f) {
  uint32_t bad = kFlagWrongBitCount | kFlagClockNotIdle | kFlagGlitch | kFlagTooLong;
  return (f.flags & bad) != 0;
}

// A frame cut by the capture window whose bits are incomplete: left out of diffs.
inline bool frame_is_partial(const Frame& f) {
  return (f.flags & (kFlagCutAtStart | kFlagCutAtEnd)) && (f.flags & kFlagWrongBitCount);
}

}  // namespace host::spi

#endif  // HOST_SPI_FRAME_H
