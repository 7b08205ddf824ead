// The planner with a height map, as a property over random maps and random paths: every
// ring entry lies on the planned segment in X/Y, its Z is the planned Z plus the map's
// offset there (the bilinear surface when cutting, the highest height when travelling),
// cutting segments come in pieces of at most 1 mm, and Z never goes below the planned
// depth minus the map's span. last_um() stays the planned position.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "firmware/core/height_map.h"
#include "host_tests/app/motion_rig.h"

namespace fake_app {
namespace {

struct Map {
  int cols, rows, pitch_x, pitch_y;
  int32_t x0, y0;
  std::vector<int16_t> h;
  double at(double x, double y) const {  // bilinear, nearest edge value outside
    const double u = std::clamp((x - x0) / pitch_x, 0.0, double(cols - 1));
    const double v = std::clamp((y - y0) / pitch_y, 0.0, double(rows - 1));
    const int i = std::min(int(u), cols - 2), j = std::min(int(v), rows - 2);
    const double fx = u - i, fy = v - j;
    auto H = [&](int c, int r) { return double(h[r * cols + c]); };
    return (1 - fy) * ((1 - fx) * H(i, j) + fx * H(i + 1, j)) +
           fy * ((1 - fx) * H(i, j + 1) + fx * H(i + 1, j + 1));
  }
};

TEST(PlannerHeightMap, EveryEntryIsThePlannedPointPlusTheMapsOffsetThere) {
  std::mt19937 rng(2511);
  for (int trial = 0; trial < 40; ++trial) {
    Map m;
    m.cols = std::uniform_int_distribution<int>(2, 16)(rng);
    m.rows = std::uniform_int_distribution<int>(2, 16)(rng);
    m.pitch_x = std::uniform_int_distribution<int>(1000, 20000)(rng);
    m.pitch_y = std::uniform_int_distribution<int>(1000, 20000)(rng);
    m.x0 = std::uniform_int_distribution<int32_t>(-5000, 5000)(rng);
    m.y0 = std::uniform_int_distribution<int32_t>(-5000, 5000)(rng);
    const int base = std::uniform_int_distribution<int>(-400, 0)(rng);
    for (int k = 0; k < m.cols * m.rows; ++k)
      m.h.push_back(int16_t(base + std::uniform_int_distribution<int>(0, 400)(rng)));
    static core::HeightMap map;
    ASSERT_TRUE(map.begin(m.cols, m.rows, m.x0, m.y0, m.pitch_x, m.pitch_y));
    for (size_t k = 0; k < m.h.size(); ++k) ASSERT_TRUE(map.set(k, m.h[k]));
    map.complete();
    const double lowest = *std::min_element(m.h.begin(), m.h.end());
    const double highest = *std::max_element(m.h.begin(), m.h.end());

    MotionRig rig;
    rig.planner.set_height_map(&map);
    const int32_t origin[3] = {0, 0, 3000};
    rig.planner.set_origin(origin);
    int32_t planned[3] = {0, 0, int32_t(3000 - highest)};
    for (int i = 0; i < 3; ++i) ASSERT_EQ(planned[i], rig.planner.last_um()[i]) << "origin";
    const double umx = 1000.0 / config::usteps_per_mm(rig.cfg.axis[0]);
    const double umz = 1000.0 / config::usteps_per_mm(rig.cfg.axis[2]);
    double prev_xy[2] = {0, 0};
    for (int step = 0; step < 60; ++step) {
      int32_t to[3] = {planned[0], planned[1], planned[2]};
      const int kind = std::uniform_int_distribution<int>(0, 9)(rng);
      if (kind == 0) {
        to[2] = std::uniform_int_distribution<int32_t>(-300, 0)(rng);  // down to a depth
      } else if (kind == 1) {
        to[2] = std::uniform_int_distribution<int32_t>(500, 2000)(rng);  // up to travel
      } else {
        const int32_t reach = kind < 5 ? 800 : 40000;  // short (spline points) or long
        to[0] += std::uniform_int_distribution<int32_t>(-reach, reach)(rng);
        to[1] += std::uniform_int_distribution<int32_t>(-reach, reach)(rng);
      }
      // A long cut fills the ring: the caller pushes again with the same target once the tick
      // has taken some (last_um() stays where it was until the whole segment is in).
      std::vector<app::PlanEntry> got;
      app::PlanEntry e;
      for (int tries = 0; !rig.planner.push(&rig.ring, to, 5000, app::kPointEndOfItem, 0);
           ++tries) {
        ASSERT_LT(tries, 100);
        for (int i = 0; i < 3; ++i) ASSERT_EQ(planned[i], rig.planner.last_um()[i]);
        while (rig.ring.pop(&e)) got.push_back(e);
      }
      while (rig.ring.pop(&e)) got.push_back(e);
      for (int i = 0; i < 3; ++i) ASSERT_EQ(to[i], rig.planner.last_um()[i]);
      const bool cutting = to[2] <= 0 && planned[2] <= 0;
      const double len = std::hypot(double(to[0] - planned[0]), double(to[1] - planned[1]));
      int pieces = 0;
      for (const app::PlanEntry& entry : got) {
        e = entry;
        ++pieces;
        const double x = e.target_usteps[0] * umx, y = e.target_usteps[1] * umx;
        const double z = e.target_usteps[2] * umz;
        // On the planned segment in X/Y (within the micrometre rounding).
        const double dx = to[0] - planned[0], dy = to[1] - planned[1];
        const double t =
            len > 0 ? ((x - planned[0]) * dx + (y - planned[1]) * dy) / (len * len) : 1.0;
        const double off = len > 0 ? std::abs((x - planned[0]) * dy - (y - planned[1]) * dx) / len
                                   : std::hypot(x - to[0], y - to[1]);
        ASSERT_LE(off, 1.5) << "trial " << trial << " step " << step;
        const double pz = planned[2] + std::clamp(t, 0.0, 1.0) * (to[2] - planned[2]);
        const double want = pz + (pz > 0 ? highest : m.at(x, y));
        ASSERT_NEAR(z, want, 2.0) << "trial " << trial << " step " << step;
        ASSERT_GE(z, pz + lowest - 2.0);  // never below the plan by more than the span
        if (cutting) {
          ASSERT_LE(std::hypot(x - prev_xy[0], y - prev_xy[1]), 1000 * std::sqrt(2.0) + 2)
              << "a cutting piece longer than 1 mm";
        }
        prev_xy[0] = x;
        prev_xy[1] = y;
      }
      if (cutting) EXPECT_GE(pieces, int(len / 1000 * std::sqrt(0.5)));
      for (int i = 0; i < 3; ++i) planned[i] = to[i];
    }
  }
}

}  // namespace
}  // namespace fake_app
