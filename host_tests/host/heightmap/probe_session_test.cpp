// Probing a model blank into a map: order, twice, re-probes and refusals.
#include "host/lib/heightmap/probe_session.h"

#include <gtest/gtest.h>

#include <fmt/format.h>  // fmt::format

#include <cmath>  // std::abs

#include "host/lib/heightmap/surface_model.h"

namespace host::heightmap {
namespace {

const AreaMm kJob{5, 5, 85, 65};

ProbeOptions every_10mm() {
  ProbeOptions o;
  o.grid.spacing_mm = 10;
  o.grid.margin_mm = 1;
  return o;
}

TEST(ProbeSession, TheMapHoldsWhatTheProbeReadAtEachGridPoint) {
  SurfaceModel blank(parse_surface_spec("tilt=0.1mm,bow=0.2mm,noise=2um,seed=5"),
                     AreaMm{0, 0, 90, 70});
  std::vector<std::pair<double, double>> touched;
  const ProbeRun run = probe_blank(kJob, every_10mm(), [&](double x, double y) {
    touched.push_back({x, y});
    return blank.probe_um(x, y);
  });
  const HeightMap& m = run.map;
  EXPECT_EQ(m.cols, 10);  // 82 mm / 10 -> 9 gaps
  EXPECT_EQ(m.rows, 8);   // 62 mm / 10 -> 7 gaps
  EXPECT_EQ(run.touches, 80u);
  EXPECT_TRUE(run.reprobed.empty());
  EXPECT_FALSE(m.repeatability_um);
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c)
      EXPECT_NEAR(m.height_um(r, c), blank.height_um(m.x_mm(c), m.y_mm(r)), 2.0);
  // In serpentine order: each touch a grid step from the last.
  for (size_t i = 1; i < touched.size(); ++i)
    EXPECT_NEAR(
        std::abs(touched[i].first - touched[i - 1].first) +
            std::abs(touched[i].second - touched[i - 1].second),
        std::abs(touched[i].first - touched[i - 1].first) > 1e-9 ? m.pitch_x_mm : m.pitch_y_mm,
        1e-9);
}

TEST(ProbeSession, TwiceRecordsTheRepeatability) {
  SurfaceModel blank(parse_surface_spec("bow=0.2mm,noise=2um,seed=5"), AreaMm{0, 0, 90, 70});
  ProbeOptions o = every_10mm();
  o.twice = true;
  const ProbeRun run =
      probe_blank(kJob, o, [&](double x, double y) { return blank.probe_um(x, y); });
  EXPECT_EQ(run.touches, 160u);
  ASSERT_TRUE(run.map.repeatability_um);
  EXPECT_GT(*run.map.repeatability_um, 2.0);  // +-2 um noise: two touches differ by up to 4
  EXPECT_LE(*run.map.repeatability_um, 4.0);
}

// The grid point (row 4, col 4) of every_10mm() over kJob: pitches 82/9 and 62/7 mm.
const double kX44 = 4 + 4 * 82.0 / 9, kY44 = 4 + 4 * 62.0 / 7;

TEST(ProbeSession, ABadTouchIsProbedAgainAndReplaced) {
  SurfaceModel blank(parse_surface_spec("tilt=0.1mm"), AreaMm{0, 0, 90, 70});
  int touches_at_bad = 0;
  const ProbeRun run = probe_blank(kJob, every_10mm(), [&](double x, double y) {
    // A chip under the bit at row 4, col 4 the first time only.
    if (std::abs(x - kX44) < 1e-6 && std::abs(y - kY44) < 1e-6 && touches_at_bad++ == 0)
      return blank.height_um(x, y) + 80.0;
    return blank.height_um(x, y);
  });
  EXPECT_EQ(touches_at_bad, 2);
  EXPECT_EQ(run.touches, 81u);
  ASSERT_EQ(run.reprobed.size(), 1u);
  EXPECT_EQ(run.reprobed[0].rfind("row 4, col 4 at (40.444, 39.429) mm reads", 0), 0u)
      << run.reprobed[0];
  EXPECT_NEAR(run.map.height_um(4, 4), blank.height_um(kX44, kY44), 1e-6);
}

TEST(ProbeSession, APointThatStillDisagreesIsRefusedWithItsPlace) {
  SurfaceModel blank(parse_surface_spec(fmt::format("bump={}mm:{}mm:1mm:60um", kX44, kY44)),
                     AreaMm{0, 0, 90, 70});
  try {
    probe_blank(kJob, every_10mm(), [&](double x, double y) { return blank.height_um(x, y); });
    FAIL() << "a dent-sized bump under one point was taken into the map";
  } catch (const ProbeRefused& e) {
    EXPECT_NE(std::string(e.what()).find("1 probe point still disagrees with its neighbours by "
                                         "more than 25 um"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("row 4, col 4 at (40.444, 39.429) mm"), std::string::npos)
        << e.what();
  }
}

TEST(ProbeSession, TwoTouchesFarApartAreRefused) {
  int n = 0;
  ProbeOptions o = every_10mm();
  o.twice = true;
  EXPECT_THROW(probe_blank(kJob, o, [&](double, double) { return ++n == 2 ? 40.0 : 0.0; }),
               ProbeRefused);
}

TEST(ProbeSession, ATouchFailurePassesThrough) {
  EXPECT_THROW(
      probe_blank(kJob, every_10mm(),
                  [](double, double) -> double { throw std::runtime_error("no contact"); }),
      std::runtime_error);
}

}  // namespace
}  // namespace host::heightmap
