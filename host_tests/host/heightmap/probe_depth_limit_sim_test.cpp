// The safety rule for probing, end to end on the simulated machine: every probe
// move has a depth limit. A grid probed through the controller (controller_touch) never
// takes the tool below the surface it touches (beyond the stop's overshoot), and a blank
// that is not there (no contact) stops the descent at the limit: nothing goes below it.
#include <gtest/gtest.h>

#include <algorithm>  // std::min
#include <limits>     // std::numeric_limits

#include "host/lib/heightmap/controller_map.h"
#include "host/lib/heightmap/probe_session.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_machine.h"

namespace host::heightmap {
namespace {

struct Rig {
  explicit Rig(std::function<int32_t(int32_t, int32_t)> surface_um) {
    sim::SimOptions o;
    o.surface_um = std::move(surface_um);
    machine = std::make_unique<sim::SimMachine>(o);
    machine->set_sample_sink(
        [this](const sim::ToolSample& s) { lowest_z_mm = std::min(lowest_z_mm, s.z_mm); });
    SenderOptions so;
    so.clock = [this] { return sim::machine_clock(*machine); };
    link = std::make_unique<sim::SimLink>(*machine);
    sender = std::make_unique<Sender>(*link, so);
    sender->open_session();
  }
  std::unique_ptr<sim::SimMachine> machine;
  std::unique_ptr<sim::SimLink> link;
  std::unique_ptr<Sender> sender;
  double lowest_z_mm = std::numeric_limits<double>::infinity();
};

ProbeOptions grid_3x3() {
  ProbeOptions o;
  o.grid.rows = o.grid.cols = 3;
  o.grid.margin_mm = 0;
  return o;
}

TEST(ProbeDepthLimit, TouchesStopAtTheSurface) {
  // A tilted blank, 0.3 mm below the zero at its far corner.
  Rig rig([](int32_t x_um, int32_t y_um) { return -(x_um + y_um) / 200; });
  const ProbeMotion m;
  const ProbeRun run =
      probe_blank(AreaMm{0, 0, 30, 30}, grid_3x3(), controller_touch(*rig.sender, m));
  EXPECT_EQ(run.map.rows, 3);
  const double surface_low_mm = -0.3;
  // After the contact the chip ramps Z to rest from the probe feed: v^2 / 2a, 1 mm/s at the
  // simulated Z acceleration is about 10 um (11.3 um measured) below the contact.
  EXPECT_GE(rig.lowest_z_mm, surface_low_mm - 0.015) << "a touch went on below the surface";
  EXPECT_LE(rig.lowest_z_mm, surface_low_mm + 0.005);
}

TEST(ProbeDepthLimit, NoContactStopsTheDescentAtTheLimit) {
  Rig rig(nullptr);  // no blank under the tool: the probe never closes
  const ProbeMotion m;
  EXPECT_THROW(probe_blank(AreaMm{0, 0, 30, 30}, grid_3x3(), controller_touch(*rig.sender, m)),
               ProbeFailed);
  EXPECT_GE(rig.lowest_z_mm, m.limit_z_mm - 0.001) << "the descent went past its limit";
  EXPECT_LE(rig.lowest_z_mm, m.limit_z_mm + 0.001) << "the descent stopped short of its limit";
}

}  // namespace
}  // namespace host::heightmap
