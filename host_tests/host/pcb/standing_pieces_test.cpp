// standing_pieces (columns joined along their sides) against one Clipper difference of the
// whole frame (the reference): the same material, split into the same connected pieces.
#include "host/lib/pcb/standing_pieces.h"

#include <gtest/gtest.h>

#include <cmath>   // std::acos, std::cos, std::sin
#include <map>     // std::map
#include <random>  // std::mt19937
#include <set>     // std::set
#include <string>  // std::to_string

#include "host/lib/pcb/disc_outline.h"

namespace host::pcb {
namespace {

const double kRadiusNm = 100000, kArcTolNm = 200;
const double kPi = std::acos(-1.0);

BoxNm box(cInt x0, cInt y0, cInt x1, cInt y1) {
  BoxNm b;
  b.add(IntPoint(x0, y0));
  b.add(IntPoint(x1, y1));
  return b;
}

// A rectangle as an outline (clockwise, like the swept outlines).
Path rectangle(cInt x0, cInt y0, cInt x1, cInt y1) {
  return Path{IntPoint(x0, y0), IntPoint(x0, y1), IntPoint(x1, y1), IntPoint(x1, y0)};
}

std::vector<StandingPiece> reference(const BoxNm& frame, const Paths& outlines) {
  ClipperLib::Clipper c;
  c.AddPath(rectangle(frame.min_x, frame.min_y, frame.max_x, frame.max_y), ClipperLib::ptSubject,
            true);
  c.AddPaths(outlines, ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctDifference, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return pieces_of(tree);
}

// The whole holding p, or -1 where there is no material.
long whole_at(const std::vector<StandingPiece>& pieces, const IntPoint& p) {
  for (const StandingPiece& piece : pieces) {
    if (piece.holds(p)) return static_cast<long>(piece.whole);
  }
  return -1;
}

size_t wholes(const std::vector<StandingPiece>& pieces) {
  std::set<size_t> w;
  for (const StandingPiece& p : pieces) w.insert(p.whole);
  return w.size();
}

// Sampled on a grid that misses the columns' sides and the rectangles' edges: material in
// both or neither, and the reference's pieces and the wholes one to one.
void expect_same_pieces(const BoxNm& frame, const Paths& outlines, size_t column_vertices,
                        const char* what) {
  const std::vector<StandingPiece> want = reference(frame, outlines);
  const std::vector<StandingPiece> got = standing_pieces(frame, outlines, column_vertices);
  std::map<long, long> to_got, to_want;
  size_t material = 0;
  const cInt step = (frame.max_x - frame.min_x) / 97 | 1;
  for (cInt x = frame.min_x + 1; x < frame.max_x; x += step) {
    for (cInt y = frame.min_y + 1; y < frame.max_y; y += step) {
      const long w = whole_at(want, IntPoint(x, y));
      const long g = whole_at(got, IntPoint(x, y));
      ASSERT_EQ(w < 0, g < 0) << what << " at " << x << ", " << y;
      if (w < 0) continue;
      ++material;
      EXPECT_EQ(to_got.emplace(w, g).first->second, g) << what << " at " << x << ", " << y;
      EXPECT_EQ(to_want.emplace(g, w).first->second, w) << what << " at " << x << ", " << y;
    }
  }
  EXPECT_GT(material, 100U) << what;
}

TEST(StandingPieces, RandomToolWalksGiveTheWholeFramesPiecesInAnyNumberOfColumns) {
  std::mt19937 rng(24);
  std::uniform_int_distribution<cInt> at(0, 8000000);
  std::normal_distribution<double> turn(0, 0.5);
  const BoxNm frame = box(0, 0, 8000000, 8000000);
  for (int scene = 0; scene < 6; ++scene) {
    Paths outlines;
    for (int w = 0; w < 30; ++w) {
      Path walk{IntPoint(at(rng), at(rng))};
      double heading = turn(rng) * 6;
      for (int k = 0; k < 40; ++k) {
        heading += turn(rng);
        walk.emplace_back(walk.back().X + static_cast<cInt>(60000 * std::cos(heading)),
                          walk.back().Y + static_cast<cInt>(60000 * std::sin(heading)));
      }
      outlines.push_back(disc_sweep_outline(walk, kRadiusNm, kArcTolNm));
    }
    for (size_t per_column : {1000000, 5000, 700, 100}) {
      const std::string what =
          "scene " + std::to_string(scene) + ", " + std::to_string(per_column) + " per column";
      expect_same_pieces(frame, outlines, per_column, what.c_str());
      EXPECT_EQ(wholes(standing_pieces(frame, outlines, per_column)),
                reference(frame, outlines).size())
          << what;
    }
  }
}

TEST(StandingPieces, ARingAcrossAColumnSideKeepsWhatItEnclosesApart) {
  // A closed isolation loop around a pad, swept and united as Clipper gives it (an outer
  // boundary and a hole), crossing the side between two columns: the pad's material and the
  // material around the ring are two pieces on both sides of it.
  const BoxNm frame = box(0, 0, 4000000, 4000000);
  Path loop;
  for (int i = 0; i <= 200; ++i) {
    const double a = 2 * kPi * i / 200;
    loop.emplace_back(2000000 + static_cast<cInt>(700000 * std::cos(a)),
                      2000000 + static_cast<cInt>(500000 * std::sin(a)));
  }
  const Paths ring = union_of({disc_sweep_outline(loop, kRadiusNm, kArcTolNm)});
  ASSERT_EQ(ring.size(), 2U);  // outer and hole
  for (size_t per_column : {1000000, 300, 100, 40}) {
    const std::vector<StandingPiece> got = standing_pieces(frame, ring, per_column);
    EXPECT_EQ(wholes(got), 2U) << per_column;
    EXPECT_NE(whole_at(got, IntPoint(2000001, 2000001)), whole_at(got, IntPoint(100001, 100001)))
        << per_column;
    expect_same_pieces(frame, ring, per_column, "ring");
  }
}

TEST(StandingPieces, CutsAlongAColumnSideSeparateAndStretchesAlongItJoin) {
  // Two columns meet at x = 1 000 000. Full-height cuts with an edge on that side, and a
  // ring of rectangles whose edges lie on it, on a grid through it.
  const BoxNm frame = box(0, 0, 2000000, 2000000);
  const Paths cut_at_side{rectangle(1000000, -10, 1100000, 2000010)};
  // 4 vertices at 2 a column: 2 columns.
  const std::vector<StandingPiece> two = standing_pieces(frame, cut_at_side, 2);
  EXPECT_EQ(wholes(two), 2U);
  expect_same_pieces(frame, cut_at_side, 2, "cut with an edge on the side");
  const Paths cut_left{rectangle(900000, -10, 1000000, 2000010)};
  EXPECT_EQ(wholes(standing_pieces(frame, cut_left, 2)), 2U);
  expect_same_pieces(frame, cut_left, 2, "cut ending on the side");

  // A square ring around the middle, its left and right sides on the column sides of 4
  // columns (x = 500 000, 1 500 000): inside and outside stay apart.
  const Paths square_ring{
      rectangle(500000, 500000, 600000, 1500000), rectangle(1400000, 500000, 1500000, 1500000),
      rectangle(500000, 500000, 1500000, 600000), rectangle(500000, 1400000, 1500000, 1500000)};
  const std::vector<StandingPiece> four = standing_pieces(frame, square_ring, 4);
  EXPECT_EQ(wholes(four), 2U);
  EXPECT_NE(whole_at(four, IntPoint(1000001, 1000001)), whole_at(four, IntPoint(1, 1)));
  expect_same_pieces(frame, square_ring, 4, "square ring on the sides");
  // A gap in the ring at a column side joins them again.
  const Paths open_ring{
      rectangle(500000, 500000, 600000, 1500000), rectangle(1400000, 500000, 1500000, 1500000),
      rectangle(500000, 500000, 950000, 600000), rectangle(1050000, 500000, 1500000, 600000),
      rectangle(500000, 1400000, 1500000, 1500000)};
  EXPECT_EQ(wholes(standing_pieces(frame, open_ring, 5)), 1U);
  expect_same_pieces(frame, open_ring, 5, "open square ring");
}

TEST(StandingPieces, NoOutlinesLeaveTheFrameStandingInOnePiece) {
  const BoxNm frame = box(-5, -7, 3000000, 1000000);
  const std::vector<StandingPiece> got = standing_pieces(frame, Paths{}, 1);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_TRUE(got[0].holds(IntPoint(0, 0)));
  EXPECT_FALSE(got[0].holds(IntPoint(3000001, 0)));
}

}  // namespace
}  // namespace host::pcb
