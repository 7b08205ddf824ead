// The height map (#A, #E) through the Application on the kinematic plant: cutting points
// (#G targets, spline points) follow the map's surface, travel keeps its clearance over the
// highest point, the frames of the job are the same with and without the map; refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "host_tests/app/app_rig.h"

namespace fake_app {
namespace {

using proto::ErrorCode;

// 4 x 3 points, 20 mm apart from (0, 0): a tilt and a bow, 190 um from lowest to highest.
const int kCols = 4, kRows = 3, kPitch = 20000;
const int32_t kHeights[kRows][kCols] = {
    {0, -40, -95, -130}, {25, -20, -80, -120}, {60, 10, -50, -90}};

double surface(double x, double y) {
  const double u = std::clamp(x / kPitch, 0.0, double(kCols - 1));
  const double v = std::clamp(y / kPitch, 0.0, double(kRows - 1));
  const int i = std::min(int(u), kCols - 2), j = std::min(int(v), kRows - 2);
  const double fx = u - i, fy = v - j;
  return (1 - fy) * ((1 - fx) * kHeights[j][i] + fx * kHeights[j][i + 1]) +
         fy * ((1 - fx) * kHeights[j + 1][i] + fx * kHeights[j + 1][i + 1]);
}

void send_map(TestHost* host) {
  host->queue(proto::HeightMapHeaderCmd{kCols, kRows, 0, 0, kPitch, kPitch});
  proto::HeightMapDataCmd d{};
  d.index = 0;
  d.height_n = 8;
  for (int k = 0; k < 8; ++k) d.height_um[k] = kHeights[k / kCols][k % kCols];
  host->queue(d);
  d.index = 8;
  d.height_n = 4;
  for (int k = 0; k < 4; ++k) d.height_um[k] = kHeights[2][k];
  host->queue(d);
}

struct Ready : AppRig {
  Ready() {
    EXPECT_TRUE(open_session());
    EXPECT_TRUE(zero_here());
    plant.record = true;
  }
};

const int32_t kTravelZ = 2000, kDepth = -100;

// Travel up, to the start, down to the depth, two straight cuts, up, home.
void queue_cuts(TestHost* host) {
  host->queue(proto::ZMoveCmd{kTravelZ, 5000});
  host->queue(proto::RapidMoveCmd{5000, 5000});
  host->queue(proto::ZMoveCmd{kDepth, 2000});
  host->queue(proto::FeedMoveCmd{55000, 35000, 8000});
  host->queue(proto::FeedMoveCmd{10000, 30000, 8000});
  host->queue(proto::ZMoveCmd{kTravelZ, 5000});
  host->queue(proto::RapidMoveCmd{0, 0});
}

struct Errors {
  double cut_max = 0;     // |z - (depth + surface)| over the cutting points
  double travel_max = 0;  // |z - (travel + highest)| over the travel points moving in X/Y
  int cut_points = 0, travel_points = 0;
};

Errors measure(const std::vector<P3>& path, bool with_map) {
  Errors e;
  const double highest = with_map ? 60 : 0;
  for (size_t k = 1; k < path.size(); ++k) {
    const P3& p = path[k];
    const P3& q = path[k - 1];
    const bool moves_xy = std::hypot(p.x - q.x, p.y - q.y) > 0.05;
    if (!moves_xy) continue;  // Z-only moves (plunges, lifts) go between the two heights
    if (p.z < 1000) {
      const double want = kDepth + (with_map ? surface(p.x, p.y) : 0);
      e.cut_max = std::max(e.cut_max, std::abs(p.z - want));
      ++e.cut_points;
    } else {
      e.travel_max = std::max(e.travel_max, std::abs(p.z - (kTravelZ + highest)));
      ++e.travel_points;
    }
  }
  return e;
}

TEST(AppHeightMap, StraightCutsFollowTheSurfaceAndTravelClearsTheHighestPoint) {
  Ready rig;
  send_map(&rig.host);
  queue_cuts(&rig.host);
  ASSERT_TRUE(rig.run_job(120000));
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_TRUE(rig.app.height_map().active());
  const Errors e = measure(rig.recorded_um(), true);
  EXPECT_GT(e.cut_points, 1000);
  EXPECT_GT(e.travel_points, 100);
  EXPECT_LE(e.cut_max, 3.0) << "cut depth off the surface";
  EXPECT_LE(e.travel_max, 1.5);

  // The same frames without a map: a flat cut at the depth (and the check above is not
  // met by it: the surface spans 190 um).
  Ready flat;
  queue_cuts(&flat.host);
  ASSERT_TRUE(flat.run_job(120000));
  EXPECT_LE(measure(flat.recorded_um(), false).cut_max, 1.5);
  EXPECT_GT(measure(flat.recorded_um(), true).cut_max, 50.0);
}

TEST(AppHeightMap, SplinePointsFollowTheSurfaceOnTheSamePathInXY) {
  const core::Spline s = blob_spline(30000, 20000, 15000, 12);
  std::vector<std::vector<P3>> runs;
  for (const bool with_map : {true, false}) {
    Ready rig;
    if (with_map) send_map(&rig.host);
    rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
    rig.host.queue(proto::RapidMoveCmd{s.control[0].x_um, s.control[0].y_um});
    rig.host.queue(proto::ZMoveCmd{kDepth, 2000});
    for (const auto& f : spline_frames(s, 8000)) rig.host.queue(f);
    rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
    ASSERT_TRUE(rig.run_job(200000));
    EXPECT_TRUE(rig.host.errors.empty());
    const Errors e = measure(rig.recorded_um(), with_map);
    EXPECT_GT(e.cut_points, 1000);
    EXPECT_LE(e.cut_max, 3.0) << (with_map ? "with" : "without") << " the map";
    runs.push_back(rig.recorded_um());
  }
  // X/Y of the cut: the same curve (each cutting point of one run within 2 um of the other's).
  std::vector<P3> a, b;
  for (const P3& p : runs[0])
    if (p.z < 1000) a.push_back(p);
  for (const P3& p : runs[1])
    if (p.z < 1000) b.push_back(p);
  double worst = 0;
  ASSERT_GT(a.size(), 1000u);
  for (size_t k = 0; k < a.size(); k += a.size() / 50) {
    double best = 1e9;
    for (size_t m = 0; m < b.size(); m += 2)
      best = std::min(best, std::hypot(a[k].x - b[m].x, a[k].y - b[m].y));
    worst = std::max(worst, best);
  }
  EXPECT_LE(worst, 2.0);
}

TEST(AppHeightMap, ClearingTheMapGoesBackToThePlannedDepth) {
  Ready rig;
  send_map(&rig.host);
  rig.host.queue(proto::HeightMapHeaderCmd{0, 0, 0, 0, 0, 0});
  queue_cuts(&rig.host);
  ASSERT_TRUE(rig.run_job(120000));
  EXPECT_FALSE(rig.app.height_map().active());
  EXPECT_LE(measure(rig.recorded_um(), false).cut_max, 1.5);
}

bool refused(const TestHost& h, ErrorCode code, uint8_t detail) {
  for (const auto& e : h.errors)
    if (e.code == code && e.detail == detail) return true;
  return false;
}

TEST(AppHeightMap, HeightsOutOfSequenceOrSpanningMoreThanAMillimetreAreRefused) {
  Ready rig;
  proto::HeightMapDataCmd d{};
  d.index = 0;
  d.height_n = 4;
  rig.host.queue(d);  // no #A
  rig.run(300);
  EXPECT_TRUE(refused(rig.host, ErrorCode::kHeightMap, proto::kHeightMapSequence));

  Ready span;
  span.host.queue(proto::HeightMapHeaderCmd{2, 2, 0, 0, 10000, 10000});
  d.index = 1;  // not the next one expected
  span.host.queue(d);
  span.run(300);
  EXPECT_TRUE(refused(span.host, ErrorCode::kHeightMap, proto::kHeightMapSequence));

  Ready wide;
  wide.host.queue(proto::HeightMapHeaderCmd{2, 2, 0, 0, 10000, 10000});
  proto::HeightMapDataCmd all{};
  all.index = 0;
  all.height_n = 4;
  const int32_t warped[4] = {600, 0, -500, 100};  // 1.1 mm from lowest to highest
  std::copy(warped, warped + 4, all.height_um);
  wide.host.queue(all);
  wide.run(300);
  EXPECT_TRUE(refused(wide.host, ErrorCode::kHeightMap, proto::kHeightMapSpan));
  wide.run(300);
  EXPECT_FALSE(wide.app.height_map().active()) << "a refused map is never switched on";
}

}  // namespace
}  // namespace fake_app
