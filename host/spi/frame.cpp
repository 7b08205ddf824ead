// Names for frame diagnostics.
#include "host/spi/frame.h"

namespace host::spi {

std::vector<std::string> flag_names(uint32_t flags) {
  static const struct {
    uint32_t bit;
    const char* name;
  } kNames[] = {{kFlagWrongBitCount, "wrong-bit-count"},
                {kFlagCutAtStart, "cut-at-start"},
                {kFlagCutAtEnd, "cut-at-end"},
                {kFlagClockNotIdle, "clock-not-idle"},
                {kFlagGlitch, "glitch"},
                {kFlagTooLong, "too-long"}};
  std::vector<std::string> out;
  for (const auto& n : kNames)
    if (flags & n.bit) out.push_back(n.name);
  return out;
}

}  // namespace host::spi
