// Depth of cut against the true surface, with and without the map the controller followed.
#include "host/lib/heightmap/depth_meter.h"

#include <gtest/gtest.h>

#include <cmath>  // std::tan

namespace host::heightmap {
namespace {

const AreaMm kBoard{0, 0, 100, 80};

// A straight isolation cut along y = 40 from x = 0 to 100 at the planned height, every 5 um
// (a sample a millisecond at 5 mm/s), Z raised by `map` where there is one.
DepthReport cut_across(const SurfaceModel& truth, const HeightMap* map, DepthOptions o) {
  DepthMeter meter(truth, map, o);
  meter.add(0, 40, 2.0);  // travel height: not isolation
  for (int i = 0; i <= 20000; ++i) {
    const double x = i * 0.005;
    meter.add(x, 40, o.isolation_z_mm + (map ? map->interpolate_um(x, 40) / 1000.0 : 0.0));
  }
  meter.add(100, 40, 2.0);
  return meter.report();
}

TEST(DepthMeter, AFlatBlankIsCutAtThePlannedDepthAndWidth) {
  const SurfaceModel flat(SurfaceSpec{}, kBoard);
  const DepthReport r = cut_across(flat, nullptr, DepthOptions{});
  EXPECT_NEAR(r.length_mm, 100.0, 1e-6);
  EXPECT_DOUBLE_EQ(r.max_error_um, 0);
  EXPECT_DOUBLE_EQ(r.rms_error_um, 0);
  EXPECT_DOUBLE_EQ(r.min_depth_um, 50);
  EXPECT_DOUBLE_EQ(r.min_width_um, 200);
  EXPECT_DOUBLE_EQ(r.uncut_mm, 0);
}

TEST(DepthMeter, ATiltIsCutDeeperWhereTheBlankRisesAndTheGrooveWidens) {
  const SurfaceModel tilted(parse_surface_spec("tilt=0.1mm"), kBoard);
  const DepthReport r = cut_across(tilted, nullptr, DepthOptions{});
  EXPECT_NEAR(r.max_error_um, 100, 1e-6);  // at x = 100 the copper is 0.1 mm higher
  EXPECT_NEAR(r.max_error_at_mm[0], 100, 1e-6);
  EXPECT_NEAR(r.rms_error_um, 100 / std::sqrt(3.0), 0.01);  // of a ramp 0 .. 100
  // A 30 degree V-bit: 0.1 mm deeper is 2 * 100 * tan(15 deg) = 53.6 um wider (issue 25).
  EXPECT_NEAR(r.max_width_um - 200, 53.59, 0.01);
  EXPECT_NEAR(r.max_width_error_um, 53.59, 0.01);
}

TEST(DepthMeter, CopperNotCutThroughWhereTheBlankFallsAway) {
  const SurfaceModel tilted(parse_surface_spec("tilt=-0.1mm"), kBoard);
  const DepthReport r = cut_across(tilted, nullptr, DepthOptions{});
  // Depth 50 - x um: below the 35 um of copper for x > 15 mm.
  EXPECT_NEAR(r.uncut_mm, 85.0, 0.01);
  EXPECT_NEAR(r.uncut_share, 0.85, 1e-4);
  EXPECT_NEAR(r.min_depth_um, -50, 1e-6);  // above the copper at the far end
}

TEST(DepthMeter, FollowingAMapOfTheSurfaceLeavesOnlyTheMapsError) {
  const SurfaceModel warped(parse_surface_spec("tilt=0.1mm,bow=0.2mm"), kBoard);
  HeightMap map;
  map.rows = 9;
  map.cols = 11;
  map.pitch_x_mm = 10;
  map.pitch_y_mm = 10;
  for (int r = 0; r < map.rows; ++r)
    for (int c = 0; c < map.cols; ++c) map.heights_um.push_back(warped.height_um(c * 10, r * 10));
  const DepthReport with = cut_across(warped, &map, DepthOptions{});
  const DepthReport without = cut_across(warped, nullptr, DepthOptions{});
  EXPECT_NEAR(with.length_mm, 100.0, 1e-6);  // the raised path is still found as isolation
  // Bilinear over 10 mm cells of a 200 um bow over 100 mm: 0.08 um/mm^2 * 10^2 / 8 = 1 um.
  EXPECT_LE(std::abs(with.max_error_um), 1.0 + 1e-9);
  EXPECT_GT(std::abs(without.max_error_um), 150.0);
}

}  // namespace
}  // namespace host::heightmap
