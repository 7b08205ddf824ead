// The least clearance of a board run's simulated cuts: the same figure and place as measuring
// every sample, though most samples are not measured.
#include "host/lib/commands/simulated_isolation.h"

#include <gtest/gtest.h>

#include <cmath>   // std::sin, std::cos
#include <limits>  // std::numeric_limits
#include <vector>  // std::vector

#include "host/lib/pcb/board_job.h"      // BoardJob
#include "host/lib/pcb/pcb_geometry.h"   // copper_islands
#include "host/lib/sim/contour_error.h"  // NearestSegment

namespace host::commands {
namespace {

TEST(SimulatedIsolation, TheLeastClearanceIsEverySamplesLeast) {
  // Two 2 mm square pads 1 mm apart; a cut that wanders round them, samples 2 um apart, and
  // a planned path between them.
  const ClipperLib::Paths copper = {
      {{0, 0}, {2000000, 0}, {2000000, 2000000}, {0, 2000000}},
      {{3000000, 0}, {5000000, 0}, {5000000, 2000000}, {3000000, 2000000}}};
  pcb::BoardJob job;
  job.copper_machine = pcb::copper_islands(copper);
  job.tool_radius_mm = 0.1;
  std::vector<Point2> cut;
  for (int i = 0; i <= 8000; ++i) {
    const double a = 2 * M_PI * i / 8000;
    const double r = 2.0 + 0.05 * std::sin(7 * a) + 0.02 * std::cos(31 * a);
    cut.push_back(Point2(2.5 + 1.9 * r * std::cos(a), 1.0 + 0.95 * r * std::sin(a)));
  }
  job.isolation_paths_mm = {{Point2(2.5, -1.0), Point2(2.5, 3.0)}};
  const SimulatedIsolation s = check_simulated_isolation(job, 0.003, {cut}, cut.size());

  std::vector<std::vector<Point2>> edges;
  for (const ClipperLib::Path& p : copper) {
    std::vector<Point2> line;
    for (const ClipperLib::IntPoint& q : p) line.push_back(Point2(q.X * 1e-6, q.Y * 1e-6));
    line.push_back(line.front());
    edges.push_back(line);
  }
  const sim::NearestSegment every(edges, 0.25);
  double least_um = std::numeric_limits<double>::infinity();
  Point2 at(0, 0);
  for (const Point2& p : cut) {
    const double c = (every.distance(p) - 0.1) * 1000.0;
    if (c < least_um) least_um = c, at = p;
  }
  EXPECT_EQ(s.min_clearance_um, least_um);
  EXPECT_EQ(s.min_clearance_at_mm, at);
  EXPECT_LT(least_um, 400.0);                            // the cut comes near the copper somewhere
  EXPECT_NEAR(s.planned_min_clearance_um, 400.0, 1e-6);  // 0.5 mm from both, less the radius
}

}  // namespace
}  // namespace host::commands
