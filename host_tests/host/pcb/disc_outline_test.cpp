// disc_sweep_outline against Clipper's round offset of the same path (the reference): both
// put their arc chords within the arc tolerance inside the true swept region, so what one
// covers and the other does not is at most a band of that width along the boundary.
#include "host/lib/pcb/disc_outline.h"

#include <gtest/gtest.h>

#include <algorithm>  // std::min
#include <cmath>      // std::acos, std::cos, std::fabs, std::hypot, std::sin
#include <random>     // std::mt19937

#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb {
namespace {

const double kRadiusNm = 100000, kArcTolNm = 200;

double perimeter(const Paths& ps) {
  double s = 0;
  for (const Path& p : ps)
    for (size_t i = 0; i < p.size(); ++i) {
      const IntPoint& a = p[i];
      const IntPoint& b = p[(i + 1) % p.size()];
      s += std::hypot(static_cast<double>(b.X - a.X), static_cast<double>(b.Y - a.Y));
    }
  return s;
}

Paths clippers_sweep(const Path& p) {
  ClipperLib::ClipperOffset o;
  o.ArcTolerance = kArcTolNm;
  Path q = p;
  if (q.size() == 1) q.push_back(q[0]);
  o.AddPath(q, ClipperLib::jtRound, ClipperLib::etOpenRound);
  Paths out;
  o.Execute(out, kRadiusNm);
  return out;
}

Paths outline_filled(const Path& p) {
  return union_of({disc_sweep_outline(p, kRadiusNm, kArcTolNm)});
}

// The two regions agree to the chords: each side's excess is within the tolerance's band
// along the boundary, and the area is the disc sweep's.
void expect_same_region(const Path& p, const char* what) {
  const Paths want = clippers_sweep(p);
  const Paths got = outline_filled(p);
  const double band = kArcTolNm * perimeter(want);
  ASSERT_GT(signed_area(want), 0) << what;
  EXPECT_LT(std::fabs(signed_area(difference_of(got, want))), band) << what;
  EXPECT_LT(std::fabs(signed_area(difference_of(want, got))), band) << what;
}

TEST(DiscOutline, ASmoothDenselySampledLoopIsClippersSweepWithoutItsSpikes) {
  // A wavy ring of 1.2 mm sampled every 10 um, its ends meeting (a tool's isolation loop).
  Path loop;
  const int n = 754;
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n, r = 1.2e6 * (1 + 0.05 * std::sin(5 * a));
    loop.emplace_back(static_cast<ClipperLib::cInt>(r * std::cos(a)),
                      static_cast<ClipperLib::cInt>(r * std::sin(a)));
  }
  expect_same_region(loop, "loop");
  // No spikes back to the vertices (Clipper's inside corners): every point of the outline of
  // an open part of the ring (its end caps clear of its start) is on the swept region's
  // boundary, a radius (less the chords' tolerance) from the path.
  const Path part(loop.begin(), loop.begin() + n * 4 / 5);
  double nearest = 1e300;
  for (const IntPoint& q : disc_sweep_outline(part, kRadiusNm, kArcTolNm))
    for (const IntPoint& v : part)
      nearest = std::min(
          nearest, std::hypot(static_cast<double>(q.X - v.X), static_cast<double>(q.Y - v.Y)));
  EXPECT_GT(nearest, kRadiusNm - kArcTolNm - 2);
  expect_same_region(part, "an open part of the ring");
  // The ring's hole stays open (a band of about 1.5 mm2; the filled ring would be 5.3).
  EXPECT_LT(signed_area(outline_filled(loop)), 0.5 * 3.1416 * 1.2e6 * 1.2e6);
}

TEST(DiscOutline, SharpTurnsReversalsRepeatsAndShortEdgesGiveTheSameRegion) {
  using P = IntPoint;
  expect_same_region({P(0, 0)}, "a point: a disc");
  expect_same_region({P(0, 0), P(0, 0)}, "a repeated point");
  expect_same_region({P(0, 0), P(500000, 0)}, "one edge");
  expect_same_region({P(0, 0), P(500000, 0), P(0, 0)}, "straight back");
  expect_same_region({P(0, 0), P(500000, 0), P(1000000, 0)}, "straight on");
  expect_same_region({P(0, 0), P(500000, 0), P(500000, 0), P(500000, 400000)}, "repeat at a turn");
  expect_same_region({P(0, 0), P(500000, 0), P(0, 10000)}, "a hairpin");
  expect_same_region({P(0, 0), P(500000, 0), P(510000, 300000), P(520000, 0), P(1000000, 0)},
                     "a spike shorter than the tool");
  expect_same_region({P(0, 0), P(1000000, 0), P(1000000, 1000000), P(0, 1000000), P(0, 0)},
                     "a closed square (inside corners)");
  expect_same_region({P(0, 0), P(0, 1000000), P(1000000, 1000000), P(1000000, 0), P(0, 0)},
                     "a closed square the other way (outside corners)");
  expect_same_region({P(0, 0), P(1000000, 1000000), P(1000000, 0), P(0, 1000000)},
                     "crossing itself");
  // Random walks: sharp turns both ways, steps shorter and longer than the tool, walks back.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> step(-300000, 300000);
  for (int k = 0; k < 60; ++k) {
    Path p{P(0, 0)};
    for (int i = 0; i < 25; ++i) {
      if (i % 7 == 3 && p.size() >= 2) {
        p.push_back(p[p.size() - 2]);  // back along the last edge
        continue;
      }
      p.emplace_back(p.back().X + step(rng), p.back().Y + step(rng));
    }
    expect_same_region(p, "a random walk");
  }
}

// Points on one straight line, their directions equal but for rounding: the outline is the
// two sides and the two round ends, no circle at a vertex (a turn of -1e-17 rad read as a
// whole turn gave 688 points here, 88 now).
TEST(DiscOutline, AStraightRunOfManyPointsHasOnlyItsTwoRoundEnds) {
  Path p;
  for (int k = 0; k < 20; ++k) p.emplace_back(2420 * k * (k + 1) / 2, 8720 * k * (k + 1) / 2);
  const size_t ends =
      2 * (static_cast<size_t>(3.1416 / (2 * std::acos(1 - kArcTolNm / kRadiusNm))) + 2);
  EXPECT_LE(disc_sweep_outline(p, kRadiusNm, kArcTolNm).size(), 4 * p.size() + ends);
  expect_same_region(p, "a straight run");
}

// The outline runs clockwise (left side forward, right side back): negative on the swept
// region, for every path, so the outlines of many paths unite under the non-zero rule.
TEST(DiscOutline, RunsClockwiseWhicheverWayThePathTurns) {
  using P = IntPoint;
  EXPECT_LT(ClipperLib::Area(disc_sweep_outline({P(0, 0), P(500000, 0)}, kRadiusNm, kArcTolNm)), 0);
  const Path ccw{P(0, 0), P(1000000, 0), P(1000000, 1000000), P(0, 1000000), P(0, 0)};
  const Path cw(ccw.rbegin(), ccw.rend());
  for (const Path& p : {ccw, cw}) {
    // Inside the ring's band: winding -1; in the ring's hole: 0.
    ClipperLib::Clipper c;
    c.AddPath(disc_sweep_outline(p, kRadiusNm, kArcTolNm), ClipperLib::ptSubject, true);
    Paths negative;
    c.Execute(ClipperLib::ctUnion, negative, ClipperLib::pftNegative, ClipperLib::pftNegative);
    Paths nonzero = outline_filled(p);
    EXPECT_NEAR(signed_area(negative), signed_area(nonzero), 1e-9 * signed_area(nonzero));
  }
}

TEST(DiscOutline, NothingForNoPathOrNoRadius) {
  EXPECT_TRUE(disc_sweep_outline({}, kRadiusNm, kArcTolNm).empty());
  EXPECT_TRUE(disc_sweep_outline({IntPoint(0, 0), IntPoint(9, 9)}, 0, kArcTolNm).empty());
}

}  // namespace
}  // namespace host::pcb
