// The isolation check sweeps only the tool-centre runs near copper: nothing near is left out.
#include "host/lib/pcb/near_copper.h"

#include <gtest/gtest.h>

#include <algorithm>  // std::reverse

#include "host_tests/host/pcb/synthetic_board.h"

namespace host::pcb {
namespace {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

const double kMm = 1e6;  // nm

IntPoint at(double x_mm, double y_mm) {
  return IntPoint(static_cast<ClipperLib::cInt>(x_mm * kMm),
                  static_cast<ClipperLib::cInt>(y_mm * kMm));
}

TEST(NearCopper, AFarPathHasNoRunAndACrossingPathKeepsOnlyItsNearSegments) {
  const Paths copper = {test::rect(0, 0, 10, 10)};
  EXPECT_TRUE(runs_near_copper({{at(20, 0), at(20, 10), at(30, 10)}}, copper, 0.1 * kMm).empty());
  // Left of the copper, across it, right of it: the segment across it, and the two beside
  // it that reach within 0.1 mm (the first and last stay 5 mm away).
  const Path across = {at(-20, 5), at(-5, 5), at(-0.05, 5), at(10.05, 5), at(15, 5), at(30, 5)};
  const Paths runs = runs_near_copper({across}, copper, 0.1 * kMm);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0], (Path{at(-5, 5), at(-0.05, 5), at(10.05, 5), at(15, 5)}));
}

TEST(NearCopper, APathInsideCopperFarFromItsEdgesIsKeptAndOneInAHoleIsNot) {
  // A 40 mm pour with a 20 mm hole in its middle.
  Path hole = test::rect(10, 10, 30, 30);
  std::reverse(hole.begin(), hole.end());
  const Paths copper = {test::rect(0, 0, 40, 40), hole};
  const Path in_pour = {at(2, 2), at(2, 8), at(8, 8)};
  const Path in_hole = {at(15, 15), at(25, 15), at(25, 25)};
  const Paths runs = runs_near_copper({in_pour, in_hole}, copper, 0.1 * kMm);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0], in_pour);
}

TEST(NearCopper, ASegmentJustWithinReachIsKept) {
  const Paths copper = {test::rect(0, 0, 10, 10)};
  // 0.1 mm from the edge: within a reach of 0.1 mm (the filter adds a micrometre of margin);
  // 0.102 mm: beyond it.
  EXPECT_EQ(runs_near_copper({{at(-0.1, 2), at(-0.1, 8)}}, copper, 0.1 * kMm).size(), 1u);
  EXPECT_TRUE(runs_near_copper({{at(-0.102, 2), at(-0.102, 8)}}, copper, 0.1 * kMm).empty());
  // A single point (a plunge) near the corner.
  EXPECT_EQ(runs_near_copper({{at(10.05, 10.05)}}, copper, 0.1 * kMm).size(), 1u);
}

}  // namespace
}  // namespace host::pcb
