// clip_to_box: the part of polygons inside a box, used to keep Clipper's sweep small when a
// board-wide net meets a small island; Clipper's own intersection is the reference. sweep_open:
// a large set of paths swept in groups against each path swept alone.
#include <gtest/gtest.h>

#include <cmath>   // std::fabs, std::hypot
#include <random>  // std::mt19937

#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb {
namespace {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

BoxNm box(ClipperLib::cInt x0, ClipperLib::cInt y0, ClipperLib::cInt x1, ClipperLib::cInt y1) {
  BoxNm b;
  b.add(IntPoint(x0, y0));
  b.add(IntPoint(x1, y1));
  return b;
}

Paths rect(const BoxNm& b) {
  return {{{b.min_x, b.min_y}, {b.max_x, b.min_y}, {b.max_x, b.max_y}, {b.min_x, b.max_y}}};
}

TEST(ClipToBox, ConcaveShapeClippedAcrossItsNotchHasTheSameAreaAsClippersIntersection) {
  // A U open at the top: the box cuts both arms, so the clip doubles back along its top side.
  const Paths u = {{{0, 0},
                    {3000, 0},
                    {3000, 3000},
                    {2000, 3000},
                    {2000, 1000},
                    {1000, 1000},
                    {1000, 3000},
                    {0, 3000}}};
  const BoxNm b = box(500, 500, 2500, 2000);
  const double clipped = signed_area(union_of(clip_to_box(u, b)));
  const double reference = signed_area(intersection_of(u, rect(b)));
  EXPECT_NEAR(clipped, reference, 1.0);
  EXPECT_NEAR(reference, 2000.0 * 1500 - 1000.0 * 1000, 1.0);
}

TEST(ClipToBox, HoleAndOuterKeepTheirSignsAndDisjointPathsAreDropped) {
  const Paths ring = {{{0, 0}, {4000, 0}, {4000, 4000}, {0, 4000}},
                      {{1000, 1000}, {1000, 3000}, {3000, 3000}, {3000, 1000}}};  // hole: CW
  const BoxNm b = box(-500, -500, 2000, 2000);
  EXPECT_NEAR(signed_area(clip_to_box(ring, b)), 2000.0 * 2000 - 1000.0 * 1000, 1.0);
  EXPECT_TRUE(clip_to_box(ring, box(5000, 5000, 6000, 6000)).empty());
  EXPECT_TRUE(clip_to_box(ring, BoxNm{}).empty());
}

// Random star-shaped (so concave) polygons: intersecting the clipped parts gives the same area
// as intersecting the whole polygons, which is what find_narrow_gaps relies on.
TEST(ClipToBox, IntersectionOfClippedPartsEqualsIntersectionOfWholePolygons) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> radius(2e5, 1e6);
  auto star = [&](double cx, double cy) {
    Path p;
    for (int k = 0; k < 40; ++k) {
      const double a = 2 * M_PI * k / 40, r = radius(rng);
      p.emplace_back(std::llround(cx + r * std::cos(a)), std::llround(cy + r * std::sin(a)));
    }
    return Paths{p};
  };
  for (int trial = 0; trial < 50; ++trial) {
    const Paths a = star(0, 0), b = star(9e5, 3e5);
    const BoxNm common = common_box(box_of(a), box_of(b));
    ASSERT_FALSE(common.empty());
    const double whole = signed_area(intersection_of(a, b));
    const double parts =
        signed_area(intersection_of(clip_to_box(a, common), clip_to_box(b, common)));
    EXPECT_NEAR(parts, whole, 1e-6 * whole + 2e3) << trial;  // rounding of crossings to 1 nm
  }
}

TEST(CommonBox, IsTheOverlapOrEmpty) {
  const BoxNm c = common_box(box(0, 0, 10, 10), box(5, -5, 20, 7));
  EXPECT_EQ(c.min_x, 5);
  EXPECT_EQ(c.min_y, 0);
  EXPECT_EQ(c.max_x, 10);
  EXPECT_EQ(c.max_y, 7);
  EXPECT_TRUE(common_box(box(0, 0, 1, 1), box(2, 2, 3, 3)).empty());
}

// A board's worth of paths is swept in groups of neighbours whose unions are then joined;
// the region must be the one of every path swept alone.
TEST(SweepOpen, PathsSweptInGroupsCoverWhatEachPathSweptAloneCovers) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(0, 80e6), step(-0.5e6, 0.5e6);
  Paths paths;
  size_t vertices = 0;
  while (vertices < 25000) {  // many groups (1 000 vertices each)
    Path p{IntPoint(static_cast<ClipperLib::cInt>(coord(rng)),
                    static_cast<ClipperLib::cInt>(coord(rng)))};
    for (int k = 0; k < 11; ++k) {
      p.emplace_back(p.back().X + static_cast<ClipperLib::cInt>(step(rng)),
                     p.back().Y + static_cast<ClipperLib::cInt>(step(rng)));
    }
    vertices += p.size();
    paths.push_back(p);
  }
  const double radius_nm = 0.1e6, arc_tol_nm = 200;
  Paths alone;
  for (const Path& p : paths) {
    const Paths s = sweep_open({p}, radius_nm, arc_tol_nm);
    alone.insert(alone.end(), s.begin(), s.end());
  }
  const Paths expected = union_of(alone);
  const Paths grouped = sweep_open(paths, radius_nm, arc_tol_nm);
  const double area = signed_area(expected);
  ASSERT_GT(area, 1e13);  // over 10 mm2: the paths cover a real part of the field
  // The same region, but for crossings rounded to 1 nm in a different order: what either has
  // and the other lacks is below a millionth (a lost group of paths would be a tenth).
  EXPECT_NEAR(signed_area(grouped), area, 1e-6 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(grouped, expected))), 1e-6 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(expected, grouped))), 1e-6 * area);
  // Unjoined (outlines built directly, not Clipper's offset), each path is an outline of
  // its own, clockwise, overlapping the others (their areas add up to more than the union),
  // and their non-zero union is the same region to the arcs' chords: either side's excess
  // within a band of the arc tolerance along the boundary (a lost path would be far more).
  const Paths unjoined = sweep_open_unjoined(paths, radius_nm, arc_tol_nm);
  ASSERT_EQ(unjoined.size(), paths.size());
  for (const Path& p : unjoined) EXPECT_LT(ClipperLib::Area(p), 0);
  EXPECT_GT(-signed_area(unjoined), area * 1.001);
  std::vector<Paths> outlines;
  for (const Path& p : unjoined) outlines.push_back(Paths{p});
  const Paths joined = united_by_strips(outlines, union_of);
  double boundary_nm = 0;
  for (const Path& p : expected)
    for (size_t i = 0; i < p.size(); ++i)
      boundary_nm += std::hypot(static_cast<double>(p[(i + 1) % p.size()].X - p[i].X),
                                static_cast<double>(p[(i + 1) % p.size()].Y - p[i].Y));
  const double band = arc_tol_nm * boundary_nm;
  ASSERT_LT(band, 1e-2 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(joined, expected))), band);
  EXPECT_LT(std::fabs(signed_area(difference_of(expected, joined))), band);
}

// Rings with a smaller ring in their hole (islands in holes, holes in those), scattered so
// that many overlap, united in strips: the strips' results are joined group by group, each
// hole with its own outer. The same region as one union of everything, no polygon on
// another (the signed areas agree), as many outers and holes.
TEST(UnitedByStrips, JoiningTheStripsKeepsEachHoleWithItsOwnOuter) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> centre(0, 60e6);
  auto circle = [](double cx, double cy, double r, bool hole) {
    Path p;
    for (int k = 0; k < 48; ++k) {
      const double a = (hole ? -2 : 2) * M_PI * k / 48;
      p.emplace_back(static_cast<ClipperLib::cInt>(cx + r * std::cos(a)),
                     static_cast<ClipperLib::cInt>(cy + r * std::sin(a)));
    }
    return p;
  };
  std::vector<Paths> pieces;
  Paths all;
  size_t vertices = 0;
  while (vertices < 40000) {  // many strips (1 000 vertices each)
    const double cx = centre(rng), cy = centre(rng);
    pieces.push_back({circle(cx, cy, 1.5e6, false), circle(cx, cy, 1.0e6, true)});
    pieces.push_back({circle(cx, cy, 0.7e6, false), circle(cx, cy, 0.3e6, true)});
    for (const Paths& p : {pieces[pieces.size() - 2], pieces.back()})
      all.insert(all.end(), p.begin(), p.end());
    vertices += 4 * 48;
  }
  const Paths expected = union_of(all);
  const Paths joined = united_by_strips(pieces, union_of);
  auto count = [](const Paths& paths, bool outer) {
    size_t n = 0;
    for (const Path& p : paths) n += ClipperLib::Orientation(p) == outer ? 1 : 0;
    return n;
  };
  const double area = signed_area(expected);
  ASSERT_GT(area, 1e14);
  ASSERT_GT(count(expected, false), 100u);  // many holes, some of them islands' holes
  EXPECT_NEAR(signed_area(joined), area, 1e-9 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(joined, expected))), 1e-9 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(expected, joined))), 1e-9 * area);
  EXPECT_EQ(count(joined, true), count(expected, true));
  EXPECT_EQ(count(joined, false), count(expected, false));
}

// Rings (an outer and its hole) over a field, grown island by island in strips: the same
// region as Clipper's own offset of all of them at once, every hole kept.
TEST(OffsetClosed, GrowingManyIslandsInStripsGivesClippersOwnOffset) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> centre(0, 100e6);
  Paths rings;
  size_t vertices = 0;
  while (vertices < 50000) {  // many strips (1 000 vertices each)
    const double cx = centre(rng), cy = centre(rng);
    Path outer, hole;
    for (int k = 0; k < 64; ++k) {
      const double a = 2 * M_PI * k / 64;
      outer.emplace_back(static_cast<ClipperLib::cInt>(cx + 1e6 * std::cos(a)),
                         static_cast<ClipperLib::cInt>(cy + 1e6 * std::sin(a)));
      hole.emplace_back(static_cast<ClipperLib::cInt>(cx + 0.6e6 * std::cos(-a)),
                        static_cast<ClipperLib::cInt>(cy + 0.6e6 * std::sin(-a)));
    }
    rings.push_back(outer);
    rings.push_back(hole);
    vertices += outer.size() + hole.size();
  }
  const Paths copper = union_of(rings);
  const double delta_nm = 0.15e6, arc_tol_nm = 500;
  ClipperLib::ClipperOffset whole;
  whole.ArcTolerance = arc_tol_nm;
  whole.AddPaths(copper, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  Paths expected;
  whole.Execute(expected, delta_nm);
  const Paths grown = offset_closed(copper, delta_nm, arc_tol_nm);
  const double area = signed_area(expected);
  ASSERT_GT(area, 1e15);  // over 1 000 mm2 of rings
  EXPECT_NEAR(signed_area(grown), area, 1e-6 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(grown, expected))), 1e-6 * area);
  EXPECT_LT(std::fabs(signed_area(difference_of(expected, grown))), 1e-6 * area);
}

}  // namespace
}  // namespace host::pcb
