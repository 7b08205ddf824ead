// Test-only VCD generator: SPI datagrams in any mode, with the faults a bench capture can
// have (a dropped clock pulse, a glitch, a cut-off end, swapped probes).
#ifndef HOST_TESTS_SPI_VCD_SYNTH_H
#define HOST_TESTS_SPI_VCD_SYNTH_H

#include <algorithm>  // std::stable_sort
#include <cstdint>    // uint32_t
#include <string>     // std::string
#include <vector>     // std::vector

namespace spi_test {

struct Word {
  uint64_t mosi;
  uint64_t miso;
};

struct Synth {
  int mode = 3;
  int bits = 32;
  int64_t half_ns = 400;    // SCK half period (1.25 MHz)
  int64_t setup_ns = 800;   // CS fall to first edge, last edge to CS rise
  int64_t gap_ns = 5000;    // CS high between datagrams
  int drop_bit_frame = -1;  // leave out the clock pulse of bit drop_bit in this frame
  int drop_bit = 0;
  int glitch_frame = -1;  // add a 20 ns pulse in the middle of bit glitch_bit
  int glitch_bit = 0;
  int64_t cut_at_ns = -1;  // end the capture here
  bool swap_data_names = false;
  const char* cs_name = "CS";
  const char* sck_name = "SCK";

  // Times of chip-select fall of each frame (filled by vcd()).
  std::vector<int64_t> frame_start_ns;

  std::string vcd(const std::vector<Word>& words) {
    struct Ev {
      int64_t t;
      char id;
      int v;
    };
    std::vector<Ev> ev;
    const int cpol = mode >> 1, cpha = mode & 1;
    int64_t t = 1000;
    frame_start_ns.clear();
    for (size_t f = 0; f < words.size(); ++f) {
      frame_start_ns.push_back(t);
      ev.push_back({t, 'c', 0});
      int64_t first = t + setup_ns;
      for (int i = 0; i < bits; ++i) {
        int mo = (words[f].mosi >> (bits - 1 - i)) & 1;
        int mi = (words[f].miso >> (bits - 1 - i)) & 1;
        int64_t lead = first + 2 * half_ns * i, trail = lead + half_ns;
        int64_t set = cpha ? lead : (i == 0 ? t : lead - half_ns);
        ev.push_back({set, 'o', mo});
        ev.push_back({set, 'i', mi});
        bool dropped = (int)f == drop_bit_frame && i == drop_bit;
        if (!dropped) {
          ev.push_back({lead, 'k', !cpol});
          ev.push_back({trail, 'k', cpol});
        }
        if ((int)f == glitch_frame && i == glitch_bit) {
          int64_t mid = trail + half_ns / 2;
          ev.push_back({mid, 'k', !cpol});
          ev.push_back({mid + 20, 'k', cpol});
        }
      }
      t = first + 2 * half_ns * bits - half_ns + setup_ns;
      ev.push_back({t, 'c', 1});
      t += gap_ns;
    }
    int64_t end = t;
    if (cut_at_ns >= 0) end = cut_at_ns;
    std::stable_sort(ev.begin(), ev.end(), [](const Ev& a, const Ev& b) { return a.t < b.t; });
    std::string s = "$timescale 1ns $end\n$scope module spi $end\n";
    s += std::string("$var wire 1 c ") + cs_name + " $end\n";
    s += std::string("$var wire 1 k ") + sck_name + " $end\n";
    s += std::string("$var wire 1 o ") + (swap_data_names ? "MISO" : "MOSI") + " $end\n";
    s += std::string("$var wire 1 i ") + (swap_data_names ? "MOSI" : "MISO") + " $end\n";
    s += "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n1c\n";
    s += std::to_string(cpol) + "k\n0o\n0i\n$end\n";
    int64_t now = 0;
    for (const Ev& e : ev) {
      if (e.t > end) break;
      if (e.t != now) s += "#" + std::to_string(e.t) + "\n", now = e.t;
      s += std::to_string(e.v) + e.id + "\n";
    }
    if (now < end) s += "#" + std::to_string(end) + "\n";
    return s;
  }
};

}  // namespace spi_test

#endif  // HOST_TESTS_SPI_VCD_SYNTH_H
