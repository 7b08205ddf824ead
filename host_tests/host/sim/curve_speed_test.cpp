// Small-radius curves through the simulated machine: the tool must stay on a circle whose
// radius is like an isolation tool's (the small arcs round pads), not only on the gentle
// curves of a drawing. Bounds come from the machine's physics and the planner's stated
// tolerances, not from a recorded run. (The planner's curve speed itself is tested in
// host_tests/app/planner_test.cpp: exact arcs get points far enough apart that the corner
// limit alone already holds the speed here.)
#include <gtest/gtest.h>

#include <cmath>  // M_PI

#include "firmware/config/machine_config.h"
#include "host/lib/sim/cut_paths.h"
#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using test::circle_curve;
using test::drawing_of;
using test::plan_of;

TEST(CurveSpeed, ToolRadiusCirclesStayWithinThePlannedTolerancesAtFullFeed) {
  const config::MachineConfig m = config::default_machine_config();
  const double a_chip_mm_s2 = m.axis[config::kAxisX].accel_um_per_s2 / 1000.0;
  for (const double radius_mm : {0.1, 0.25}) {
    const double feed_mm_s = 10;  // v^2 / R = 1000 and 400 mm/s^2: beyond the chip's ramp
    const JobPlan plan = plan_of(drawing_of({circle_curve(20, 20, radius_mm)}), feed_mm_s);
    sim::SimJobOptions o;
    o.sender.status_interval = std::chrono::milliseconds(2);
    const sim::SimJobResult r = sim::run_sim_job(plan, o);
    ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
    // The points lie on the circle with chords within the chord tolerance (5 um); the planner
    // allows 4 um of ramp error at a corner and 2 um of corner cut by switching targets.
    EXPECT_LE(r.max_contour_error_um, 5.0 + 4.0 + 2.0) << "R " << radius_mm << " mm";
    // No machine goes round faster than its acceleration allows (v^2 / R <= a_chip); the
    // planned centripetal budget is 0.66 a_chip, and the circle is not much slower than that.
    const double circumference_mm = 2 * M_PI * radius_mm;
    const double fastest_s = circumference_mm / std::sqrt(a_chip_mm_s2 * radius_mm);
    const double planned_s = circumference_mm / std::sqrt(0.66 * a_chip_mm_s2 * radius_mm);
    const double s = r.cut_s;  // pen down and moving in X/Y
    EXPECT_GE(s, fastest_s) << "R " << radius_mm << " mm";
    EXPECT_LE(s, 1.25 * planned_s + 0.1) << "R " << radius_mm << " mm";  // + plunge, stop
  }
}

// The simulated cuts at the isolation depth, for the board's copper check after `run`: a
// run at the depth that moves is a path; a plunge passing through it (a drill) is not.
TEST(CutPathCollector, KeepsMovingRunsAtTheDepthAndDropsPlungesThroughIt) {
  sim::CutPathCollector c(-0.05, 0.002);
  auto at = [&c](double x, double y, double z) { c.add(sim::ToolSample{0, x, y, z}); };
  at(0, 0, 2.0);  // travel height
  at(0, 0, -0.049);
  at(0.01, 0, -0.05);
  at(0.02, 0.01, -0.0505);
  at(0.02, 0.01, 0.5);  // lifted: the path ends
  at(5, 5, -0.0495);    // a drill plunge through the depth, no X/Y motion
  at(5, 5, -0.05);
  at(5, 5, -1.0);
  at(1, 1, -0.05);  // a second cut
  at(1.0005, 1, -0.05);
  at(1.002, 1, -0.05);
  const std::vector<std::vector<Point2>>& paths = c.paths();
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(paths[0].size(), 3u);
  EXPECT_DOUBLE_EQ(paths[0].back().x(), 0.02);
  EXPECT_EQ(paths[1].size(), 3u);
  EXPECT_EQ(c.samples(), 6u);
}

TEST(CutPathCollector, AnUnmovedLastRunIsDropped) {
  sim::CutPathCollector c(-0.05, 0.002);
  c.add(sim::ToolSample{0, 3, 3, -0.05});
  c.add(sim::ToolSample{1, 3, 3, -0.05});
  EXPECT_TRUE(c.paths().empty());
  EXPECT_EQ(c.samples(), 0u);
}

}  // namespace
}  // namespace host
