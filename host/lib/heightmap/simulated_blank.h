// The simulated blank as the simulated probe input sees it: the surface's height under the
// tool tip, with a fresh probe-noise reading for every touch (drawn when the tool comes
// down near the copper after being away, held while it stays near), so one touch reads
// one noisy height however many milliseconds the approach takes.
#ifndef HOST_LIB_HEIGHTMAP_SIMULATED_BLANK_H
#define HOST_LIB_HEIGHTMAP_SIMULATED_BLANK_H

#include <cstdint>  // int32_t

#include "host/lib/heightmap/surface_model.h"

namespace host::heightmap {

class SimulatedBlank {
 public:
  explicit SimulatedBlank(const SurfaceModel& surface) : surface_(surface) {}
  // Where the tool is (the simulator's tool samples, mm): tells a new approach.
  void tool_at(double x_mm, double y_mm, double z_mm);
  // The copper's top under (x, y) in um, this touch's noise included (the seam
  // SimOptions::surface_um calls, once a millisecond while the tool moves).
  int32_t surface_um(int32_t x_um, int32_t y_um);
  const SurfaceModel& model() const { return surface_; }

 private:
  SurfaceModel surface_;
  double tool_z_um_ = 1e9;  // far above until the first sample
  bool away_ = true;        // the tool was clear of the copper since the last draw
  double noise_um_ = 0;
};

// Clear of the copper: the tip this far above the surface ends a touch.
constexpr double kTouchClearUm = 50.0;

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_SIMULATED_BLANK_H
