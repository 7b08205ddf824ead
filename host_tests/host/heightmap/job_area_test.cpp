// A job against its height map: the area it cuts, and refusal when it leaves the map.
#include "host/lib/heightmap/job_area.h"

#include <gtest/gtest.h>

namespace host::heightmap {
namespace {

// Curves over (10, 10) .. (50, 40) mm and a hole drilled at (55, 12) mm.
JobPlan curves_and_a_hole() {
  JobPlan plan;
  plan.extents_mm.add(Point2(10, 10));
  plan.extents_mm.add(Point2(50, 40));
  PlanStep drill;
  drill.kind = PlanStep::kDrill;
  drill.to = {55000, 12000};
  plan.steps.push_back(drill);
  PlanStep rapid;  // travel does not cut: not in the area
  rapid.kind = PlanStep::kRapid;
  rapid.to = {90000, 90000};
  plan.steps.push_back(rapid);
  return plan;
}

HeightMap map_over(double x0, double y0, double x1, double y1) {
  HeightMap m;
  m.origin_x_mm = x0;
  m.origin_y_mm = y0;
  m.rows = m.cols = 2;
  m.pitch_x_mm = x1 - x0;
  m.pitch_y_mm = y1 - y0;
  m.heights_um.assign(4, 0.0);
  return m;
}

TEST(JobArea, CurvesFeedsAndHolesButNotTravel) {
  const std::optional<AreaMm> a = cutting_area(curves_and_a_hole());
  ASSERT_TRUE(a);
  EXPECT_DOUBLE_EQ(a->x0, 10);
  EXPECT_DOUBLE_EQ(a->y0, 10);
  EXPECT_DOUBLE_EQ(a->x1, 55);
  EXPECT_DOUBLE_EQ(a->y1, 40);
  EXPECT_FALSE(cutting_area(JobPlan{}));
}

TEST(JobArea, AJobInsideItsMapIsAccepted) {
  EXPECT_NO_THROW(refuse_job_outside_map(curves_and_a_hole(), map_over(9, 9, 56, 41), "m.json"));
  EXPECT_NO_THROW(refuse_job_outside_map(curves_and_a_hole(), map_over(10, 10, 55, 40), "m"));
}

TEST(JobArea, AJobLeavingItsMapIsRefusedBeforeItStarts) {
  try {
    refuse_job_outside_map(curves_and_a_hole(), map_over(9, 9, 52, 41), "m.json");
    FAIL() << "the hole at x 55 is outside the map";
  } catch (const HeightMapError& e) {
    EXPECT_EQ(std::string(e.what()),
              "m.json: the job cuts over (10.000, 10.000) .. (55.000, 40.000) mm, the map "
              "covers only (9.000, 9.000) .. (52.000, 41.000) mm: probe again over this job "
              "(--probe), the job was not started");
  }
}

}  // namespace
}  // namespace host::heightmap
