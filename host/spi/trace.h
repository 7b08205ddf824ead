// A logic-analyser capture as per-channel level changes, with times in picoseconds.
#ifndef HOST_SPI_TRACE_H
#define HOST_SPI_TRACE_H

#include <cstdint>  // int64_t
#include <string>   // std::string
#include <vector>   // std::vector

namespace host::spi {

// One digital channel: its level at the start of the window and the times it flips.
struct Channel {
  std::string name;
  bool initial_high = false;
  std::vector<int64_t> toggles_ps;  // strictly increasing

  // Level at time t, after any change at exactly t.
  bool level_at(int64_t t_ps) const;
  // Level just before t (a change at exactly t not yet applied).
  bool level_before(int64_t t_ps) const;
  // Records the level from t on; ignores a "change" to the current level.
  void set_level(int64_t t_ps, bool high);
  // Level after the last recorded change.
  bool final_level() const { return initial_high != (toggles_ps.size() % 2 == 1); }
};

// A whole capture: the channels and the window they cover.
struct Trace {
  std::vector<Channel> channels;
  int64_t start_ps = 0;
  int64_t end_ps = 0;
  int64_t sample_period_ps = 0;  // 0 when the source has no fixed sample rate
  std::string format;            // "vcd", "sigrok", "saleae-csv"

  // Index of the channel with this name (exact, then case-insensitive), or -1.
  int find(const std::string& name) const;
};

}  // namespace host::spi

#endif  // HOST_SPI_TRACE_H
