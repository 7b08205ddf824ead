// The plot's tool path: pieces that meet where the pen changes, thinning that keeps every
// change and both ends, and its size (8 bytes and a bit a position).
#include "host/lib/plan/pen_path.h"

#include <gtest/gtest.h>

#include <vector>  // std::vector

namespace host {
namespace {

struct Piece {
  std::vector<Point2> points;
  bool down;
};

std::vector<Piece> pieces_of(const PenPath& path) {
  std::vector<Piece> out;
  path.each_piece([&out](const std::vector<Point2>& p, bool down) { out.push_back({p, down}); });
  return out;
}

TEST(PenPath, APieceRunsToTheFirstPositionOfTheNext) {
  PenPath path;
  path.add({0, 0}, false);
  path.add({5, 0}, true);  // plunged here: the travel ends here and the cut begins
  path.add({5, 3}, true);
  path.add({5, 3}, false);  // lifted here
  path.add({9, 9}, false);
  const std::vector<Piece> p = pieces_of(path);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_FALSE(p[0].down);
  EXPECT_EQ(p[0].points, (std::vector<Point2>{{0, 0}, {5, 0}}));
  EXPECT_TRUE(p[1].down);
  EXPECT_EQ(p[1].points, (std::vector<Point2>{{5, 0}, {5, 3}, {5, 3}}));
  EXPECT_FALSE(p[2].down);
  EXPECT_EQ(p[2].points, (std::vector<Point2>{{5, 3}, {9, 9}}));
  EXPECT_EQ(pen_down_pieces(path).size(), 1u);
  EXPECT_TRUE(pieces_of(PenPath()).empty());
}

TEST(PenPath, ThinningKeepsTheEndsAndEveryPenChange) {
  PenPath path;
  for (int i = 0; i <= 1000; ++i) path.add(Point2(i * 0.01, 0), (i / 100) % 2 == 1);
  path.thin(0.5);
  // Ten pen changes (at 1, 2, ... 10 mm), the ends, and a position about every 0.5 mm.
  int changes = 0;
  for (size_t i = 1; i < path.size(); ++i) {
    changes += path.pen_down(i) != path.pen_down(i - 1);
    EXPECT_LE(path.point(i).x() - path.point(i - 1).x(), 0.5 + 1e-5);
  }
  EXPECT_EQ(changes, 10);
  EXPECT_EQ(path.point(0).x(), 0.0);
  EXPECT_FLOAT_EQ(path.point(path.size() - 1).x(), 10.0);
  EXPECT_LE(path.size(), 2u + 10 + 21);
  EXPECT_GE(path.size(), 21u);
  // Each piece still spans its whole millimetre; the last is the lone position at 10 mm.
  const std::vector<Piece> p = pieces_of(path);
  ASSERT_EQ(p.size(), 11u);
  for (size_t k = 0; k + 1 < p.size(); ++k)
    EXPECT_NEAR(p[k].points.back().x() - p[k].points.front().x(), 1.0, 1e-5) << k;
  EXPECT_EQ(p.back().points.size(), 1u);
}

TEST(PenPath, APositionTakesEightBytesAndABit) {
  PenPath path;
  for (int i = 0; i < 100000; ++i) path.add(Point2(i, -i), i % 2 == 0);
  EXPECT_LE(path.heap_bytes(), 100000u * 9);  // in blocks: no doubled array
  EXPECT_EQ(path.point(99999), Point2(99999, -99999));
  EXPECT_FALSE(path.pen_down(99999));
}

}  // namespace
}  // namespace host
