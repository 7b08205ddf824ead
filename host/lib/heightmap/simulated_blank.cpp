// The simulated blank under the probe (simulated_blank.h).
#include "host/lib/heightmap/simulated_blank.h"

#include <cmath>  // std::lround

namespace host::heightmap {

void SimulatedBlank::tool_at(double x_mm, double y_mm, double z_mm) {
  tool_z_um_ = z_mm * 1000.0;
  if (tool_z_um_ > surface_.height_um(x_mm, y_mm) + kTouchClearUm) away_ = true;
}

int32_t SimulatedBlank::surface_um(int32_t x_um, int32_t y_um) {
  const double h = surface_.height_um(x_um / 1000.0, y_um / 1000.0);
  // Near the copper after being away: a new touch, a new reading.
  if (away_ && tool_z_um_ <= h + kTouchClearUm) {
    noise_um_ = surface_.next_noise_um();
    away_ = false;
  }
  return static_cast<int32_t>(std::lround(h + noise_um_));
}

}  // namespace host::heightmap
