// Outline loops from strokes, the cutter offset to the outside and holding tabs.
#include "host/lib/pcb/cutout.h"

#include <gtest/gtest.h>

#include "host_tests/host/pcb/synthetic_board.h"

namespace host::pcb {
namespace {

double length(const std::vector<Point2>& p) {
  double l = 0;
  for (size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

TEST(Cutout, StrokesInAnyOrderAndDirectionCloseIntoOneLoop) {
  const ClipperLib::Paths loops = outline_loops(test::rect_outline(0, 0, 30, 20), 0.02);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_NEAR(std::fabs(ClipperLib::Area(loops[0])) / 1e12, 600.0, 1e-6);
}

TEST(Cutout, CutterRunsOutsideTheBoardAtItsRadius) {
  CutoutOptions o;
  o.cutter_diameter_mm = 2.0;
  o.tab_width_mm = 0;
  const CutoutPlan p = plan_cutout(test::rect_outline(0, 0, 30, 20), o);
  ASSERT_EQ(p.loops.size(), 1u);
  EXPECT_TRUE(p.loops[0].outer);
  ASSERT_EQ(p.loops[0].pieces.size(), 1u);
  for (const Point2& q : p.loops[0].pieces[0].points_mm) {
    // Outside the 30 x 20 rectangle by exactly the radius (edges) or on the corner arcs.
    const double dx = std::max({0.0 - q.x(), q.x() - 30.0, 0.0});
    const double dy = std::max({0.0 - q.y(), q.y() - 20.0, 0.0});
    EXPECT_NEAR(std::hypot(dx, dy), 1.0, 0.0011);
  }
  EXPECT_NEAR(p.board_area_mm2, 600.0, 1e-6);
}

TEST(Cutout, TabsLiftTheCutterForTheTabWidthPlusTheCutterDiameter) {
  CutoutOptions o;
  o.cutter_diameter_mm = 1.0;
  o.tab_width_mm = 2.0;
  o.tab_count = 4;
  const CutoutPlan p = plan_cutout(test::rect_outline(0, 0, 30, 20), o);
  EXPECT_EQ(p.tabs, 4);
  int tabs = 0;
  double total = 0;
  for (const CutoutPiece& piece : p.loops[0].pieces) {
    total += length(piece.points_mm);
    if (!piece.tab) continue;
    ++tabs;
    EXPECT_NEAR(length(piece.points_mm), 3.0, 1e-6);
  }
  EXPECT_EQ(tabs, 4);
  EXPECT_NEAR(total, 2 * (30 + 20) + 3.14159265 * 1.0, 0.01);  // perimeter + corner arcs
}

TEST(Cutout, TabSpacingGivesOneTabPerLengthOfOutline) {
  CutoutOptions o;
  o.cutter_diameter_mm = 1.0;
  o.tab_spacing_mm = 10.0;  // the cutter loop is 2 (30 + 20) + pi = 103.1 mm long
  EXPECT_EQ(plan_cutout(test::rect_outline(0, 0, 30, 20), o).tabs, 10);
  o.tab_spacing_mm = 40.0;
  EXPECT_EQ(plan_cutout(test::rect_outline(0, 0, 30, 20), o).tabs, 2);
}

TEST(Cutout, AnOutlineThatDoesNotCloseIsRefusedWithThePlace) {
  PcbLayer l = test::rect_outline(0, 0, 30, 20);
  l.polygons_nm.pop_back();  // the left edge is missing
  try {
    outline_loops(l, 0.02);
    FAIL() << "an open outline was accepted";
  } catch (const CutoutError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("test-Edge.Cuts.gbr"), std::string::npos) << m;
    EXPECT_NE(m.find("does not close"), std::string::npos) << m;
  }
}

TEST(Cutout, AnInternalCutOutIsMilledInsideWithoutTabs) {
  PcbLayer l = test::rect_outline(0, 0, 30, 20);
  l.polygons_nm.push_back(test::rect(10, 5, 20, 15));
  l.polygons_nm.back().push_back(l.polygons_nm.back().front());  // a closed stroke
  CutoutOptions o;
  o.cutter_diameter_mm = 1.0;
  const CutoutPlan p = plan_cutout(l, o);
  ASSERT_EQ(p.loops.size(), 2u);
  EXPECT_FALSE(p.loops[0].outer);  // the hole first, so the board still holds while it is cut
  EXPECT_EQ(p.loops[0].pieces.size(), 1u);
  for (const Point2& q : p.loops[0].pieces[0].points_mm) {
    EXPECT_GE(q.x(), 10.5 - 1e-6);
    EXPECT_LE(q.x(), 19.5 + 1e-6);
  }
  EXPECT_NEAR(p.board_area_mm2, 600.0 - 100.0, 1e-6);
}

}  // namespace
}  // namespace host::pcb
