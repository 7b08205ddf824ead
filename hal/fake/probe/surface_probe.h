// A probe input for the host: closes while the tool tip is at or below a board surface
// given as a function of X/Y (the simulator's blank: tilt, bow, bump, noise), or as a test
// sets it. The simulator tells it the tool tip every millisecond before the firmware's tick.
#ifndef HAL_FAKE_PROBE_SURFACE_PROBE_H
#define HAL_FAKE_PROBE_SURFACE_PROBE_H

#include <cstdint>     // int32_t
#include <functional>  // std::function
#include <utility>     // std::move

#include "hal/interfaces/probe_input.h"  // hal::ProbeInput

namespace fake {

// Height of the copper top at a machine X/Y, all in micrometres, in the frame of the tool
// position the simulator reports (SimMachine::position() x 1000). Empty: no board.
using SurfaceUm = std::function<int32_t(int32_t x_um, int32_t y_um)>;

class SurfaceProbe : public hal::ProbeInput {
 public:
  explicit SurfaceProbe(SurfaceUm surface = SurfaceUm()) : surface_(std::move(surface)) {}
  void set_surface(SurfaceUm surface) { surface_ = std::move(surface); }
  bool has_surface() const { return static_cast<bool>(surface_); }
  // Where the tool tip is now (the simulator, every ms before the firmware's tick).
  void set_tool_tip_um(int32_t x_um, int32_t y_um, int32_t z_um) {
    x_um_ = x_um;
    y_um_ = y_um;
    z_um_ = z_um;
  }
  // Forces the input closed (true) or open (false) whatever the surface says; cleared by
  // release(). For tests: a shorted clip, a broken wire.
  void force(bool closed) {
    forced_ = true;
    forced_closed_ = closed;
  }
  void release() { forced_ = false; }

  // tool_z <= surface(x, y): the tip touches (or is pressed into) the copper.
  bool closed() override {
    ++reads_;
    if (forced_) return forced_closed_;
    return surface_ && z_um_ <= surface_(x_um_, y_um_);
  }
  long reads() const { return reads_; }

 private:
  SurfaceUm surface_;
  int32_t x_um_ = 0, y_um_ = 0, z_um_ = 0;
  bool forced_ = false, forced_closed_ = false;
  long reads_ = 0;
};

}  // namespace fake

#endif  // HAL_FAKE_PROBE_SURFACE_PROBE_H
