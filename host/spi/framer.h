// Turns a capture's CS/SCK/MOSI/MISO levels into datagrams: one per chip-select period,
// each data bit read as it was just before the sampling clock edge.
#ifndef HOST_SPI_FRAMER_H
#define HOST_SPI_FRAMER_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/spi/capture.h"  // Error
#include "host/spi/frame.h"    // Frame
#include "host/spi/trace.h"    // Trace

namespace host::spi {

// Channel names (or 0-based indices as "#2") chosen by the user; empty = find by name.
// "none" for cs frames the whole capture as one stream cut every `bits` bits; "none" for
// miso/mosi leaves that line out.
struct ChannelMap {
  std::string cs, sck, mosi, miso;
};

struct FramerOptions {
  ChannelMap names;
  int mode = 3;               // SPI mode 0..3 (CPOL = mode>>1, CPHA = mode&1)
  int bits = 32;              // expected bits per datagram; 0 = whatever each period holds
  int64_t min_pulse_ps = -1;  // shorter pulses are glitches; -1 = 40 % of the median pulse
};

struct FramerResult {
  std::vector<Frame> frames;
  int cs = -1, sck = -1, mosi = -1, miso = -1;  // channel indices used (-1: none)
  int empty_periods = 0;                        // chip-select periods with no clock edge
  int64_t min_pulse_ps = 0;                     // glitch threshold actually used
};

// Which channel plays which role: the user's names, else common names (CS, CS#, nSCS_C, SS;
// SCK, CLK, SCLK; MOSI, SDI_C, SDO1; MISO, SDO_C, SDI1), else the shared captures' probe
// wiring by index (0 = CS, 1 = MOSI, 2 = SCK; no MISO) when channels are numbered.
Error resolve_channels(const Trace& trace, const ChannelMap& names, FramerResult* out);

// Frames the capture. Errors only for unusable input (missing channels, bad options).
Error frame_capture(const Trace& trace, const FramerOptions& options, FramerResult* out);

// Picoseconds from "250ns", "1.5us", "2 ms", "0"; false if unreadable.
bool parse_duration_ps(const std::string& text, int64_t* ps);

}  // namespace host::spi

#endif  // HOST_SPI_FRAMER_H
