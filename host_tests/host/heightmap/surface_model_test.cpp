// The simulated blank: the --surface text and the shape it gives.
#include "host/lib/heightmap/surface_model.h"

#include <gtest/gtest.h>

#include <cmath>  // std::abs

namespace host::heightmap {
namespace {

const AreaMm kBoard{0, 0, 100, 80};

TEST(SurfaceSpec, ReadsEveryKeyWithItsUnit) {
  const SurfaceSpec s = parse_surface_spec(
      "tilt=0.1mm,tilt_y=-20um,bow=0.2mm,bump=30mm:20mm:4mm:40um,noise=2um,"
      "seed=7,area=5mm:5mm:105mm:85mm");
  EXPECT_DOUBLE_EQ(s.tilt_x_um, 100);
  EXPECT_DOUBLE_EQ(s.tilt_y_um, -20);
  EXPECT_DOUBLE_EQ(s.bow_um, 200);
  ASSERT_TRUE(s.bump);
  EXPECT_DOUBLE_EQ(s.bump->x_mm, 30);
  EXPECT_DOUBLE_EQ(s.bump->radius_mm, 4);
  EXPECT_DOUBLE_EQ(s.bump->height_um, 40);
  EXPECT_DOUBLE_EQ(s.noise_um, 2);
  EXPECT_EQ(s.seed, 7u);
  ASSERT_TRUE(s.area);
  EXPECT_DOUBLE_EQ(s.area->x1, 105);
  // The text it prints reads back the same.
  const SurfaceSpec again = parse_surface_spec(surface_spec_text(s));
  EXPECT_EQ(surface_spec_text(again), surface_spec_text(s));
}

TEST(SurfaceSpec, RefusesALengthWithoutItsUnit) {
  try {
    parse_surface_spec("tilt=0.1");
    FAIL() << "a length without a unit was read";
  } catch (const SurfaceSpecError& e) {
    EXPECT_NE(std::string(e.what()).find("tilt=0.1: give the length with its unit"),
              std::string::npos)
        << e.what();
  }
}

TEST(SurfaceSpec, RefusesUnknownKeysAndBadValues) {
  EXPECT_THROW(parse_surface_spec("tilt=0.1mm,bwo=0.2mm"), SurfaceSpecError);
  EXPECT_THROW(parse_surface_spec("bump=1mm:2mm:3mm"), SurfaceSpecError);
  EXPECT_THROW(parse_surface_spec("bump=1mm:2mm:0mm:5um"), SurfaceSpecError);
  EXPECT_THROW(parse_surface_spec("bow=2mm"), SurfaceSpecError);  // beyond 1 mm out of flat
  EXPECT_THROW(parse_surface_spec("seed=-1"), SurfaceSpecError);
  EXPECT_THROW(parse_surface_spec("area=5mm:5mm:5mm:9mm"), SurfaceSpecError);
  EXPECT_THROW(parse_surface_spec("tilt=abcmm"), SurfaceSpecError);
  EXPECT_THROW(parse_surface_spec(""), SurfaceSpecError);
}

// A key given twice would silently take the last value: refused, naming both.
TEST(SurfaceSpec, RefusesAKeyGivenTwice) {
  for (const char* text : {"tilt=0.1mm,bow=0.2mm,tilt=0.3mm", "tilt=0.1mm,tilt_x=0.1mm",
                           "noise=2um,noise=2um", "seed=1,bow=1um,seed=2"}) {
    try {
      parse_surface_spec(text);
      ADD_FAILURE() << text;
    } catch (const SurfaceSpecError& e) {
      EXPECT_NE(std::string(e.what()).find("given twice"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(parse_surface_spec("tilt=0.1mm,tilt_y=0.2mm").tilt_y_um, 200.0);  // two keys
}

TEST(SurfaceModel, TiltRisesAcrossTheAreaAndIsZeroAtTheMachineZero) {
  const SurfaceModel m(parse_surface_spec("tilt=0.1mm"), kBoard);
  EXPECT_NEAR(m.height_um(0, 0), 0.0, 1e-9);
  EXPECT_NEAR(m.height_um(100, 40), 100.0, 1e-9);
  EXPECT_NEAR(m.height_um(50, 0), 50.0, 1e-9);
}

TEST(SurfaceModel, BowPutsTheCentreAboveTheCorners) {
  const SurfaceModel m(parse_surface_spec("bow=0.2mm"), kBoard);
  EXPECT_NEAR(m.height_um(50, 40) - m.height_um(100, 80), 200.0, 1e-9);
  EXPECT_NEAR(m.height_um(0, 80), m.height_um(0, 0), 1e-9);
  EXPECT_NEAR(m.height_um(50, 0) - m.height_um(0, 0), 100.0, 1e-9);  // an edge's middle: half
}

TEST(SurfaceModel, BumpIsLocal) {
  const SurfaceModel m(parse_surface_spec("bump=30mm:20mm:4mm:40um"), kBoard);
  EXPECT_NEAR(m.height_um(30, 20), 40.0, 1e-9);
  EXPECT_NEAR(m.height_um(32, 20), 20.0, 1e-9);
  EXPECT_NEAR(m.height_um(34.01, 20), 0.0, 1e-9);
}

TEST(SurfaceModel, ProbeNoiseStaysWithinItsBoundAndRepeatsWithTheSeed) {
  SurfaceModel a(parse_surface_spec("tilt=0.1mm,noise=2um,seed=3"), kBoard);
  SurfaceModel b(parse_surface_spec("tilt=0.1mm,noise=2um,seed=3"), kBoard);
  SurfaceModel c(parse_surface_spec("tilt=0.1mm,noise=2um,seed=4"), kBoard);
  double largest = 0;
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double pa = a.probe_um(50, 40), pb = b.probe_um(50, 40), pc = c.probe_um(50, 40);
    EXPECT_EQ(pa, pb);
    differs = differs || pa != pc;
    largest = std::max(largest, std::abs(pa - 50.0));
  }
  EXPECT_LE(largest, 2.0);
  EXPECT_GT(largest, 1.8);  // it does use its range
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace host::heightmap
