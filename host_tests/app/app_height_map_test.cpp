// The height map (#A, #E) through the Application on the kinematic plant: cutting points
// (#G targets, spline points) follow the map's surface, travel keeps its clearance over the
// highest point, the frames of the job are the same with and without the map; refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

// The map from (x0, 0); unzeroed, the machine stands at (0, 0): x0 -40 mm puts a height of
// -95 um under it.
void send_map(TestHost* host, int32_t x0_um = 0) {
  host->queue(proto::HeightMapHeaderCmd{kCols, kRows, x0_um, 0, kPitch, kPitch});
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

// Item 1 of the map's lifetime: #I (a new session, e.g. the next `engraver send`) starts
// without a map; the job after it cuts at its planned depth.
TEST(AppHeightMap, ANewSessionStartsWithoutTheMapOfTheLastOne) {
  Ready rig;
  send_map(&rig.host);
  ASSERT_TRUE(rig.run_job(5000));
  ASSERT_TRUE(rig.app.height_map().active());
  ASSERT_TRUE(rig.open_session());
  rig.run(200);
  EXPECT_FALSE(rig.app.height_map().active()) << "the map outlived its session";
  ASSERT_TRUE(rig.app.zeroed());
  rig.plant.path.clear();
  queue_cuts(&rig.host);
  ASSERT_TRUE(rig.run_job(120000));
  EXPECT_TRUE(rig.host.errors.empty());
  const Errors e = measure(rig.recorded_um(), false);
  EXPECT_GT(e.cut_points, 1000);
  EXPECT_LE(e.cut_max, 1.5) << "the last session's map compensated this job";
}

// #I with the tool down in the work under a map: the stop keeps the planned depth (the
// old map's offset where the tool stands comes off, as when a #A clears it), so the next
// X/Y move goes back to the planned depth instead of carrying the old offset on.
TEST(AppHeightMap, ANewSessionDropsTheOldMapsOffsetFromTheNextMove) {
  Ready rig;
  send_map(&rig.host);
  rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
  rig.host.queue(proto::RapidMoveCmd{40000, 20000});  // surface -80 um here
  rig.host.queue(proto::ZMoveCmd{kDepth, 2000});
  ASSERT_TRUE(rig.run_job(60000));
  ASSERT_NEAR(rig.position_um().z, kDepth - 80, 1.5);
  ASSERT_TRUE(rig.open_session());
  rig.run(200);
  EXPECT_FALSE(rig.app.height_map().active());
  rig.host.queue(proto::FeedMoveCmd{45000, 20000, 2000});
  ASSERT_TRUE(rig.run_job(60000));
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_NEAR(rig.position_um().z, kDepth, 1.5) << "the old map's offset stayed after #I";
}

// Sends the frames queue() adds and lets them run: the plant must not take a single
// microstep (every recorded sample where it stood), and the state must be idle again.
template <typename Queue>
void expect_no_motion(AppRig* rig, Queue queue, const char* what) {
  rig->run_job(20000);
  const std::array<double, 3> at = rig->plant.pos_usteps;
  rig->plant.path.clear();
  queue(&rig->host);
  ASSERT_TRUE(rig->run_job(5000)) << what;
  rig->run(300);  // anything the tick was given would have moved by now
  EXPECT_TRUE(rig->host.errors.empty()) << what;
  ASSERT_FALSE(rig->plant.path.empty());
  double worst = 0;
  for (const auto& p : rig->plant.path)
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(p[i] - at[i]));
  EXPECT_EQ(worst, 0.0) << what << ": the standing machine moved (microsteps)";
  EXPECT_EQ(rig->plant.pos_usteps, at) << what;
}

void clear_map(TestHost* host) {
  host->queue(proto::HeightMapHeaderCmd{0, 0, 0, 0, 0, 0});
}

// Item 2: loading or clearing a map never moves a standing machine, zeroed or not, the tool
// up or down in the work; the map applies from the next point the controller generates.
TEST(AppHeightMap, LoadingOrClearingAMapNeverMovesAStandingMachine) {
  struct NotZeroed : AppRig {
    NotZeroed() {
      EXPECT_TRUE(open_session());
      plant.record = true;
    }
  };
  {
    // Unzeroed: the machine stands where it was switched on; nothing moves.
    NotZeroed raw;
    ASSERT_FALSE(raw.app.zeroed());
    const auto shifted_map = [](TestHost* host) { send_map(host, -2 * kPitch); };
    expect_no_motion(&raw, shifted_map, "load, not zeroed");
    EXPECT_TRUE(raw.app.height_map().active());
    expect_no_motion(&raw, clear_map, "clear, not zeroed");
    EXPECT_FALSE(raw.app.height_map().active());
  }
  // (0, 40 mm): the surface 60 um above the zero, the map's highest point.
  const int32_t kX = 0, kY = 40000;
  for (const int32_t z : {kTravelZ, kDepth}) {
    const char* where = z > 0 ? "tool up" : "tool down";
    Ready rig;
    rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
    rig.host.queue(proto::RapidMoveCmd{kX, kY});
    rig.host.queue(proto::ZMoveCmd{z, 2000});
    expect_no_motion(
        &rig, [](TestHost* h) { send_map(h); }, where);
    EXPECT_TRUE(rig.app.height_map().active());
    expect_no_motion(&rig, clear_map, where);
    // With the map followed to the standing point (Z at the planned depth + 60 um), then
    // cleared: the tool stays (no 60 um plunge).
    send_map(&rig.host);
    rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
    rig.host.queue(proto::RapidMoveCmd{kX + 1000, kY});
    rig.host.queue(proto::ZMoveCmd{z, 2000});
    rig.host.queue(proto::FeedMoveCmd{kX, kY, 2000});
    ASSERT_TRUE(rig.run_job(20000));
    EXPECT_NEAR(rig.position_um().z, z + 60, 1.5) << where;
    expect_no_motion(&rig, clear_map, where);
    // The next motion follows the change: the next point is the planned one again (the
    // tool goes back to the planned Z along that move, not on the spot).
    rig.host.queue(proto::FeedMoveCmd{kX + 2000, kY, 2000});
    ASSERT_TRUE(rig.run_job(20000));
    EXPECT_NEAR(rig.position_um().z, z, 1.5) << where;
  }
}

// The safety rule: compensation never drives Z below the job's lowest planned depth
// minus the map's range (with Z 0). Random maps of up to 1 mm span, sent before the job or
// while the tool stands at the depth (the map then applies from the next move), a spline
// leaving the grid and cuts along its rows (over every grid point) and beyond its edges.
TEST(AppHeightMap, ZNeverGoesBelowTheLowestDepthMinusTheMapsRange) {
  uint32_t state = 12345;
  auto next = [&state](int lo, int hi) {
    state = state * 1103515245u + 12345u;
    return lo + int((state >> 8) % uint32_t(hi - lo + 1));
  };
  const core::Spline s = blob_spline(30000, 20000, 25000, 12);  // leaves the map's grid
  for (int trial = 0; trial < 6; ++trial) {
    const bool while_down = trial % 2 == 1;
    // Below Z 0 only (the map's range is then its depth: the rule is tight where the path
    // crosses the lowest grid point), or across it.
    int32_t h[12];
    const int low = trial < 4 ? next(-1000, -100) : next(-900, -100);
    const int high = trial < 4 ? 0 : low + 1000;
    for (int32_t& v : h) v = next(low, high);
    const double lowest = std::min(0, *std::min_element(h, h + 12));
    const double highest = std::max(0, *std::max_element(h, h + 12));
    Ready rig;
    auto map = [&](TestHost* host) {
      host->queue(proto::HeightMapHeaderCmd{kCols, kRows, 0, 0, kPitch, kPitch});
      proto::HeightMapDataCmd d{};
      d.height_n = 8;
      std::copy(h, h + 8, d.height_um);
      host->queue(d);
      d.index = 8;
      d.height_n = 4;
      std::copy(h + 8, h + 12, d.height_um);
      host->queue(d);
    };
    if (!while_down) map(&rig.host);
    rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
    rig.host.queue(proto::RapidMoveCmd{s.control[0].x_um, s.control[0].y_um});
    rig.host.queue(proto::ZMoveCmd{kDepth, 2000});
    if (while_down) map(&rig.host);
    for (const auto& f : spline_frames(s, 8000)) rig.host.queue(f);
    for (const int32_t y : {0, kPitch, 2 * kPitch}) {  // along each row of the grid
      rig.host.queue(proto::FeedMoveCmd{-5000, y, 8000});
      rig.host.queue(proto::FeedMoveCmd{(kCols - 1) * kPitch + 5000, y, 8000});
    }
    rig.host.queue(proto::ZMoveCmd{kTravelZ, 5000});
    ASSERT_TRUE(rig.run_job(200000)) << trial;
    EXPECT_TRUE(rig.host.errors.empty()) << trial;
    EXPECT_TRUE(rig.app.height_map().active()) << trial;
    double deepest = 1e9;
    for (const P3& p : rig.recorded_um()) deepest = std::min(deepest, p.z);
    EXPECT_GE(deepest, kDepth - (highest - lowest) - 1.0)
        << "trial " << trial << (while_down ? " (map sent with the tool down)" : "") << ": heights "
        << lowest << " .. " << highest;
  }
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
