// The simulated blank under the probe: one noise reading a touch, held through the approach.
#include "host/lib/heightmap/simulated_blank.h"

#include <gtest/gtest.h>

#include <set>  // std::set

namespace host::heightmap {
namespace {

TEST(SimulatedBlank, ATouchReadsOneNoisyHeightThroughItsWholeApproach) {
  SimulatedBlank blank(
      SurfaceModel(parse_surface_spec("tilt=0.1mm,noise=2um,seed=9"), AreaMm{0, 0, 100, 80}));
  std::set<int32_t> touches;
  for (int touch = 0; touch < 20; ++touch) {
    blank.tool_at(50, 40, 2.0);  // retracted: clear of the copper
    std::set<int32_t> during;
    // Down from 100 um above the copper (50 um) to 10 um below, a micrometre a millisecond.
    for (int z = 150; z >= 40; --z) {
      blank.tool_at(50, 40, z / 1000.0);
      const int32_t s = blank.surface_um(50000, 40000);
      if (z <= 100) during.insert(s);  // within 50 um: the touch's reading, held
    }
    ASSERT_EQ(during.size(), 1u);
    EXPECT_NEAR(*during.begin(), 50, 2);
    touches.insert(*during.begin());
  }
  EXPECT_GT(touches.size(), 2u);  // touches differ: the noise is per touch
}

TEST(SimulatedBlank, WithoutNoiseItIsTheSurface) {
  SimulatedBlank blank(SurfaceModel(parse_surface_spec("bow=0.2mm"), AreaMm{0, 0, 100, 80}));
  blank.tool_at(50, 40, 0.0);
  EXPECT_EQ(blank.surface_um(50000, 40000), 200);
  EXPECT_EQ(blank.surface_um(0, 0), 0);
}

}  // namespace
}  // namespace host::heightmap
