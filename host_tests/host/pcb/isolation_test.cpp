// Isolation contours, passes, clearing and narrow-gap detection on copper built in code.
#include "host/lib/pcb/isolation.h"

#include <gtest/gtest.h>

#include <algorithm>  // std::max, std::min
#include <cmath>      // std::hypot
#include <vector>     // std::vector

#include "host/lib/pcb/board_files.h"  // read_board_text
#include "host/lib/pcb/isolation_check.h"
#include "host/lib/pcb/pcb_geometry.h"
#include "host_tests/host/pcb/synthetic_board.h"

namespace host::pcb {
namespace {

using test::pad;
using test::rect;

std::vector<std::vector<Point2>> centre_lines(const IsolationResult& r) {
  std::vector<std::vector<Point2>> out;
  for (const ToolPathNm& t : r.paths) {
    std::vector<Point2> pts;
    for (const auto& q : t.path) pts.push_back(to_mm(q));
    if (t.closed && !pts.empty()) pts.push_back(pts.front());
    out.push_back(pts);
  }
  return out;
}

// Smallest distance from p to the copper's edges (mm).
double distance_to_copper(const Point2& p, const ClipperLib::Paths& copper) {
  double best = 1e300;
  for (const auto& path : copper) {
    for (size_t i = 0; i < path.size(); ++i) {
      const Point2 a = to_mm(path[i]), b = to_mm(path[(i + 1) % path.size()]);
      const Point2 ab = b - a;
      double t = ab.squaredNorm() > 0 ? (p - a).dot(ab) / ab.squaredNorm() : 0;
      t = std::max(0.0, std::min(1.0, t));
      best = std::min(best, (a + t * ab - p).norm());
    }
  }
  return best;
}

TEST(Isolation, OneContourPerIslandAtTheToolRadiusPlusTheClearance) {
  const ClipperLib::Paths copper = {rect(0, 0, 2, 1), pad(5, 0.5, 0.8)};
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  ASSERT_DOUBLE_EQ(o.clearance_mm, 0.008);
  const IsolationResult r = plan_isolation(copper, o);
  EXPECT_EQ(r.islands, 2u);
  EXPECT_TRUE(r.narrow_gaps.empty());
  EXPECT_DOUBLE_EQ(r.tool_radius_mm, 0.1);  // the tool's own: what the checks sweep
  ASSERT_EQ(r.paths.size(), 2u);
  for (const ToolPathNm& t : r.paths) {
    for (const auto& q : t.path) EXPECT_NEAR(distance_to_copper(to_mm(q), copper), 0.108, 0.0011);
  }
  const IsolationCheck c = check_isolation(copper, centre_lines(r), 0.1, 0.002);
  EXPECT_TRUE(c.ok()) << describe(c);
}

// A hatched plane: a 10 mm square with a 3 x 3 grid of 1 mm openings, and one 3 mm opening
// that holds a pad. Copper made as a hatch is: the plane, then every opening cut out of it.
ClipperLib::Paths hatched_plane_with_a_pad() {
  ClipperLib::Paths openings;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      openings.push_back(rect(1 + 2 * i, 1 + 2 * j, 2 + 2 * i, 2 + 2 * j));
  openings.push_back(rect(6.5, 6.5, 9.5, 9.5));
  ClipperLib::Paths copper = difference_of({rect(0, 0, 10, 10)}, openings);
  copper.push_back(pad(8, 8, 0.5));
  return copper;
}

TEST(Isolation, AHatchOpeningThatHoldsNoIslandGetsNoContour) {
  const ClipperLib::Paths copper = hatched_plane_with_a_pad();
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  const IsolationResult r = plan_isolation(copper, o);
  EXPECT_EQ(r.islands, 2u);
  EXPECT_EQ(r.empty_holes_skipped, 9u);
  // Round the plane, inside the opening that holds the pad, round the pad: three.
  ASSERT_EQ(r.paths.size(), 3u);
  for (const ToolPathNm& t : r.paths) {
    for (const auto& q : t.path) EXPECT_NEAR(distance_to_copper(to_mm(q), copper), 0.108, 0.0011);
  }
  const IsolationCheck c = check_isolation(copper, centre_lines(r), 0.1, 0.002);
  EXPECT_TRUE(c.ok()) << describe(c);
}

TEST(Isolation, HatchOpeningsAreIsolatedWhenAsked) {
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  o.isolate_empty_holes = true;
  const IsolationResult r = plan_isolation(hatched_plane_with_a_pad(), o);
  EXPECT_EQ(r.empty_holes_skipped, 0u);
  EXPECT_EQ(r.paths.size(), 12u);  // and one inside each of the nine openings
}

TEST(Isolation, GapNarrowerThanTheToolIsReportedWithItsPlace) {
  // Two pads 0.15 mm apart at x = 10.0 .. 10.15; the tool is 0.2 mm wide.
  const ClipperLib::Paths copper = {rect(8, 0, 10, 2), rect(10.15, 0, 12, 2), rect(20, 0, 21, 1)};
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  const IsolationResult r = plan_isolation(copper, o);
  EXPECT_EQ(r.islands, 3u);
  ASSERT_EQ(r.narrow_gaps.size(), 1u);
  const NarrowGap& g = r.narrow_gaps[0];
  EXPECT_NEAR(g.gap_mm, 0.15, 1e-6);
  EXPECT_NEAR(g.at.x / kNmPerMm, 10.075, 0.01);
  EXPECT_NEAR(g.at.y / kNmPerMm, 1.0, 0.1);
  // The merged contour does not cut copper, but the checker sees the islands joined.
  const IsolationCheck c = check_isolation(copper, centre_lines(r), 0.1, 0.002);
  EXPECT_TRUE(c.hits.empty()) << describe(c);
  ASSERT_EQ(c.unseparated.size(), 1u);
}

// Distance (mm) from a point to the nearest edge of some paths.
double mm_to_edges(const PointNm& at, const ClipperLib::Paths& paths) {
  double best = 1e300;
  for (const ClipperLib::Path& p : paths) {
    for (size_t i = 0; i < p.size(); ++i) {
      const double ax = static_cast<double>(p[i].X), ay = static_cast<double>(p[i].Y);
      const double dx = static_cast<double>(p[(i + 1) % p.size()].X) - ax;
      const double dy = static_cast<double>(p[(i + 1) % p.size()].Y) - ay;
      const double px = static_cast<double>(at.x) - ax, py = static_cast<double>(at.y) - ay;
      const double l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? std::max(0.0, std::min(1.0, (px * dx + py * dy) / l2)) : 0;
      best = std::min(best, std::hypot(px - t * dx, py - t * dy));
    }
  }
  return best / kNmPerMm;
}

// A gap's place is where it is narrowest, halfway between the islands (outside tester 20:
// the middle of the region both clearances cover was 5 mm off a gap round a corner, and at
// the pad's centre for a pad in a pour's opening).
TEST(Isolation, AGapIsPlacedAtItsNarrowestHalfwayBetweenTheIslands) {
  struct Case {
    const char* what;
    ClipperLib::Paths a, b;
    double gap_mm = 0.1;
  };
  ClipperLib::Paths pour = {rect(0, 0, 10, 10)};
  ClipperLib::Path opening = rect(4.4, 4.4, 5.6, 5.6);
  ClipperLib::ReversePath(opening);
  pour.push_back(opening);
  // Two arcs drawn 0.25 mm wide, their centres 0.05 mm apart: the gap narrows to 0.05 mm at
  // x = 5.15 (outside tester 21: the place was on one arc's edge, 5.125).
  const PcbLayer arcs = read_board_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,0.25*%\nD10*\nG75*\n"
      "X-4330127Y-2500000D02*\nG03*\nX-4330127Y2500000I4330127J2500000D01*\nG01*\n"
      "X-4683236Y-2675000D02*\nG03*\nX-4683236Y2675000I4633236J2675000D01*\nG01*\nM02*\n",
      "arcs.gbr", LayerKind::kCopperTop);
  const std::vector<Island> arc_islands = copper_islands(arcs.polygons_nm);
  ASSERT_EQ(arc_islands.size(), 2u);
  const std::vector<Case> cases = {
      {"arcs narrowing", arc_islands[0].paths, arc_islands[1].paths, 0.05},
      // Two tracks 0.1 mm apart turning a corner: an L with 20 mm arms.
      {"L",
       {rect(0, 0, 20, 0.25), rect(19.75, 0, 20, 20)},
       {rect(0, 0.35, 19.65, 0.6), rect(19.4, 0.35, 19.65, 20)}},
      {"pad in a pour's opening", pour, {rect(4.5, 4.5, 5.5, 5.5)}},
  };
  for (const Case& c : cases) {
    ClipperLib::Paths copper = c.a;
    copper.insert(copper.end(), c.b.begin(), c.b.end());
    IsolationOptions o;
    o.tool_width_mm = 0.2;
    const IsolationResult r = plan_isolation(copper, o);
    ASSERT_EQ(r.narrow_gaps.size(), 1u) << c.what;
    const NarrowGap& g = r.narrow_gaps[0];
    EXPECT_NEAR(g.gap_mm, c.gap_mm, 0.001) << c.what;
    EXPECT_NEAR(mm_to_edges(g.at, union_of(c.a)), g.gap_mm / 2, 0.002) << c.what;
    EXPECT_NEAR(mm_to_edges(g.at, union_of(c.b)), g.gap_mm / 2, 0.002) << c.what;
  }
}

TEST(Isolation, GapJustWiderThanTheToolAndItsClearancePasses) {
  const ClipperLib::Paths copper = {rect(8, 0, 10, 2), rect(10.22, 0, 12, 2)};
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  const IsolationResult r = plan_isolation(copper, o);
  EXPECT_TRUE(r.narrow_gaps.empty());
  const IsolationCheck c = check_isolation(copper, centre_lines(r), 0.1, 0.002);
  EXPECT_TRUE(c.ok()) << describe(c);
}

// 0.21 mm: the tool (0.2) fits, but not with 8 um to spare on both sides. Reported, since the
// contours of both pads would merge; without a clearance the tool passes.
TEST(Isolation, GapNarrowerThanTheToolAndItsClearanceIsReported) {
  const ClipperLib::Paths copper = {rect(8, 0, 10, 2), rect(10.21, 0, 12, 2)};
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  ASSERT_EQ(plan_isolation(copper, o).narrow_gaps.size(), 1u);
  o.clearance_mm = 0;
  const IsolationResult r = plan_isolation(copper, o);
  EXPECT_TRUE(r.narrow_gaps.empty());
  EXPECT_TRUE(check_isolation(copper, centre_lines(r), 0.1, 0.002).ok());
  o.clearance_mm = -0.001;
  EXPECT_THROW(plan_isolation(copper, o), std::invalid_argument);
}

TEST(Isolation, FurtherPassesStepOutByTheToolWidthLessTheOverlap) {
  const ClipperLib::Paths copper = {rect(0, 0, 1, 1)};
  IsolationOptions o;
  o.tool_width_mm = 0.2;
  o.passes = 3;
  o.overlap = 0.25;
  const IsolationResult r = plan_isolation(copper, o);
  ASSERT_EQ(r.paths.size(), 3u);
  for (const ToolPathNm& t : r.paths) {
    const double expect = 0.108 + t.pass * 0.15;  // radius + clearance, then steps
    for (const auto& q : t.path) EXPECT_NEAR(distance_to_copper(to_mm(q), copper), expect, 0.0011);
  }
}

TEST(Isolation, ClearingLeavesNoCopperFreeAreaUncut) {
  const ClipperLib::Paths copper = {rect(1, 1, 3, 2), pad(6, 3, 0.7)};
  IsolationOptions o;
  o.tool_width_mm = 0.4;
  o.clearance_mm = 0;  // the reach below is the tool's alone (a clearance leaves its band)
  o.mill_all = true;
  o.area_nm = {rect(0, 0, 8, 5)};
  const IsolationResult r = plan_isolation(copper, o);
  ClipperLib::Paths centres;
  for (const auto& line : centre_lines(r)) {
    ClipperLib::Path p;
    for (const Point2& q : line) p.push_back(test::nm(q.x(), q.y()));
    centres.push_back(p);
  }
  const ClipperLib::Paths swept = union_of(sweep_open(centres, 0.2e6, 500));
  // What a round tool can reach of the copper-free area: its opening by the tool radius
  // (the area's square corners keep r^2 (1 - pi/4) each).
  const ClipperLib::Paths free_area = difference_of({rect(0, 0, 8, 5)}, copper);
  const ClipperLib::Paths reachable =
      offset_closed(offset_closed(free_area, -0.2e6, 500), 0.2e6, 500);
  const ClipperLib::Paths uncut = difference_of(reachable, swept);
  EXPECT_LT(std::fabs(signed_area(uncut)) / 1e12, 0.001);  // under 0.001 mm2 left
  EXPECT_GT(std::fabs(signed_area(free_area)) - std::fabs(signed_area(reachable)), 0.03e12);
  const IsolationCheck c = check_isolation(copper, centre_lines(r), 0.2, 0.002);
  EXPECT_TRUE(c.ok()) << describe(c);
}

// A simulated tool path is a sample every millisecond: a straight run is thousands of
// collinear points, which the checker thins before sweeping. A short excursion toward the
// copper in such a run must survive the thinning and be reported; the straight run alone
// passes (tool 0.2 mm at 0.105 mm from the pad: 5 um to spare).
TEST(Isolation, CheckerKeepsAShortExcursionInALongStraightRunOfSamples) {
  const ClipperLib::Paths copper = {rect(0, 0, 10, 1)};
  std::vector<Point2> straight, bumped;
  for (int i = 0; i <= 1000; ++i) {
    const double x = i * 0.01;  // 10 um apart, as at 10 mm/s
    straight.push_back(Point2(x, 1.105));
    bumped.push_back(Point2(x, i == 500 ? 1.095 : 1.105));  // 5 um into the copper there
  }
  const IsolationCheck clean = check_isolation(copper, {straight}, 0.1, 0.002);
  EXPECT_TRUE(clean.ok()) << describe(clean);
  const IsolationCheck hit = check_isolation(copper, {bumped}, 0.1, 0.002);
  ASSERT_EQ(hit.hits.size(), 1u) << describe(hit);
  EXPECT_NEAR(hit.hits[0].at_mm.x(), 5.0, 0.05);
}

TEST(Isolation, CheckerSeesASampleLessThanTheToleranceOffAStraightRun) {
  // The tool shrunk by the tolerance (radius 98 um) clears the copper by 1 um along the run;
  // one sample 1.5 um off it reaches 0.5 um into the copper. Thinning the samples by more
  // than the tolerance allows would straighten it away.
  const ClipperLib::Paths copper = {rect(0, 0, 10, 1)};
  std::vector<Point2> bumped;
  for (int i = 0; i <= 1000; ++i) bumped.push_back(Point2(i * 0.01, i == 500 ? 1.0975 : 1.099));
  const IsolationCheck hit = check_isolation(copper, {bumped}, 0.1, 0.002);
  ASSERT_EQ(hit.hits.size(), 1u) << describe(hit);
  EXPECT_NEAR(hit.hits[0].at_mm.x(), 5.0, 0.01);
}

TEST(Isolation, CheckerFindsEveryHitOnABoardCheckedInStrips) {
  // 120 pads in a row, each ringed by a planned contour of 200 samples 1 um apart in
  // radius, so thinning keeps them (24 000 in all: the check works in several strips), and two
  // strokes that each cut a copper strip that runs along the whole row: one hit each, none lost or
  // split between strips.
  ClipperLib::Paths copper;
  std::vector<std::vector<Point2>> paths;
  for (int i = 0; i < 120; ++i) {
    const double x = 2.0 * i;
    copper.push_back(pad(x, 0, 0.5));
    std::vector<Point2> ring;
    for (int k = 0; k <= 200; ++k) {
      const double a = 2 * 3.14159265358979 * k / 200;
      const double r = k % 2 ? 0.6105 : 0.6095;
      ring.push_back(Point2(x + r * std::cos(a), r * std::sin(a)));
    }
    paths.push_back(ring);
  }
  copper.push_back(rect(-1, 3, 239, 3.5));
  ASSERT_TRUE(check_isolation(copper, paths, 0.1, 0.002).ok());
  paths.push_back({Point2(10.0, 2.5), Point2(10.0, 4.0)});
  paths.push_back({Point2(230.0, 2.5), Point2(230.0, 4.0)});
  const IsolationCheck c = check_isolation(copper, paths, 0.1, 0.002);
  ASSERT_EQ(c.hits.size(), 2u) << describe(c);
  EXPECT_NEAR(c.hits[0].at_mm.x() + c.hits[1].at_mm.x(), 240.0, 0.01);
}

TEST(Isolation, DescribeListsTheLargestHitsAndCountsTheRest) {
  IsolationCheck c;
  for (int i = 0; i < 25; ++i) {
    CopperHit h;
    h.area_mm2 = 0.001 * (i + 1);
    h.at_mm = Point2(i, 0);
    c.hits.push_back(h);
  }
  const std::string d = describe(c);
  EXPECT_NE(d.find("0.025000 mm2 of copper at (24.000, 0.000) mm on the machine"),
            std::string::npos)
      << d;
  EXPECT_EQ(d.find("0.001000 mm2"), std::string::npos) << d;  // the smallest is not listed
  EXPECT_NE(d.find("... and 5 smaller"), std::string::npos) << d;
}

TEST(Isolation, CheckerFindsAToolPathThroughCopper) {
  const ClipperLib::Paths copper = {rect(0, 0, 2, 2), rect(3, 0, 5, 2)};
  IsolationOptions o;
  const IsolationResult r = plan_isolation(copper, o);
  std::vector<std::vector<Point2>> paths = centre_lines(r);
  paths.push_back({Point2(-1, 1), Point2(1, 1)});  // straight into the first pad
  const IsolationCheck c = check_isolation(copper, paths, 0.1, 0.002);
  ASSERT_EQ(c.hits.size(), 1u);
  EXPECT_NEAR(c.hits[0].at_mm.x(), 0.55, 0.05);  // 0 .. 1.1 cut into the pad
  EXPECT_NEAR(c.hits[0].at_mm.y(), 1.0, 0.01);
}

TEST(Isolation, CheckerFindsIslandsWithNoCutBetweenThem) {
  const ClipperLib::Paths copper = {rect(0, 0, 2, 2), rect(3, 0, 5, 2), rect(8, 0, 9, 1)};
  // Only the third island is isolated: the first two share the uncut field.
  IsolationOptions o;
  const IsolationResult r = plan_isolation({rect(8, 0, 9, 1)}, o);
  const IsolationCheck c = check_isolation(copper, centre_lines(r), 0.1, 0.002);
  EXPECT_TRUE(c.hits.empty());
  ASSERT_EQ(c.unseparated.size(), 1u);
  EXPECT_EQ(c.islands, 3u);
}

// An island is placed by a point of what the tool leaves of it: a cut across the middle of a
// pad (where the pad's own middle lies) leaves two halves, and the pad is found in the field
// it shares with an island nobody isolated. Fails if the runs that cut an island are left
// out when its standing part is worked out (its middle, under the cut, is in no piece).
TEST(Isolation, CheckerPlacesAnIslandByThePartTheToolLeavesStanding) {
  const ClipperLib::Paths copper = {rect(0, 0, 4, 1), rect(6, 0, 7, 1)};
  const std::vector<std::vector<Point2>> cut = {{Point2(2, -1), Point2(2, 2)}};
  const IsolationCheck c = check_isolation(copper, cut, 0.1, 0.002);
  EXPECT_EQ(c.hits.size(), 1u) << describe(c);
  ASSERT_EQ(c.unseparated.size(), 1u) << describe(c);
  EXPECT_LT(c.unseparated[0].a_mm.x(), 4.0);  // a point of the cut pad, off the cut
  EXPECT_GT(std::fabs(c.unseparated[0].a_mm.x() - 2.0), 0.1);
}

// A loop around the first pad whose ends stop short of each other; the second pad is left in
// the uncut field. The tool closes the loop when its ends are less than a tool width apart.
// The separation is judged with the whole tool (radius 0.1 mm), not the one shrunk by the
// tolerance that the copper check uses.
IsolationCheck check_open_loop(double gap_mm) {
  const ClipperLib::Paths copper = {rect(0, 0, 1, 1), rect(3, 0, 4, 1)};
  const double h = gap_mm / 2;
  const std::vector<Point2> open_loop = {Point2(0.5 + h, -0.3), Point2(1.3, -0.3),
                                         Point2(1.3, 1.3),      Point2(-0.3, 1.3),
                                         Point2(-0.3, -0.3),    Point2(0.5 - h, -0.3)};
  return check_isolation(copper, {open_loop}, 0.1, 0.002);
}

TEST(Isolation, CheckerSeparatesWithTheWholeToolWidth) {
  // 0.197 mm: closed by the 0.2 mm tool, open to a 0.196 mm one (radius less tolerance).
  const IsolationCheck bridged = check_open_loop(0.197);
  EXPECT_TRUE(bridged.ok()) << describe(bridged);
  const IsolationCheck open = check_open_loop(0.203);
  EXPECT_TRUE(open.hits.empty());
  EXPECT_EQ(open.unseparated.size(), 1u) << describe(open);
}

TEST(Isolation, BadOptionsAreRefused) {
  IsolationOptions o;
  o.tool_width_mm = 0;
  EXPECT_THROW(plan_isolation({rect(0, 0, 1, 1)}, o), std::invalid_argument);
  o.tool_width_mm = 0.2;
  o.passes = 0;
  EXPECT_THROW(plan_isolation({rect(0, 0, 1, 1)}, o), std::invalid_argument);
}

}  // namespace
}  // namespace host::pcb
