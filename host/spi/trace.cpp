// Level queries on a capture channel stored as a list of change times.
#include "host/spi/trace.h"

#include <algorithm>  // std::lower_bound, std::upper_bound
#include <cctype>     // std::tolower

namespace host::spi {

bool Channel::level_at(int64_t t_ps) const {
  size_t n = std::upper_bound(toggles_ps.begin(), toggles_ps.end(), t_ps) - toggles_ps.begin();
  return initial_high != (n % 2 == 1);
}

bool Channel::level_before(int64_t t_ps) const {
  size_t n = std::lower_bound(toggles_ps.begin(), toggles_ps.end(), t_ps) - toggles_ps.begin();
  return initial_high != (n % 2 == 1);
}

void Channel::set_level(int64_t t_ps, bool high) {
  if (high == final_level()) return;
  // A second change at the same instant cancels the first (a zero-width pulse).
  if (!toggles_ps.empty() && toggles_ps.back() >= t_ps) {
    toggles_ps.pop_back();
    return;
  }
  toggles_ps.push_back(t_ps);
}

// Lower-cases ASCII for name comparison.
static std::string lower(const std::string& s) {
  std::string out = s;
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

int Trace::find(const std::string& name) const {
  for (size_t i = 0; i < channels.size(); ++i)
    if (channels[i].name == name) return static_cast<int>(i);
  std::string want = lower(name);
  for (size_t i = 0; i < channels.size(); ++i)
    if (lower(channels[i].name) == want) return static_cast<int>(i);
  return -1;
}

}  // namespace host::spi
