// The point generator's pieces of a chord (#U maximum step, split by the planner), read one
// by one from the planner's machine position: each ends within half a micrometre per axis of the
// straight line, none is longer than the step per axis, there are ceil(span / step) of them, and
// the last is the line's end (also past 65 535 pieces, where the split divides differently).
#include <gtest/gtest.h>

#include <cmath>    // std::cos, std::sin, std::lround, std::fabs, std::ceil
#include <cstdlib>  // std::labs
#include <vector>   // std::vector

#include "firmware/app/point_generator.h"
#include "firmware/core/spline.h"
#include "host_tests/app/motion_rig.h"

namespace fake_app {
namespace {

struct Piece {
  int32_t x_um, y_um;
};

// Every point the generator hands the planner for a degree-1 line from -> to at max_step:
// the ring is kept full but one, so each run() pushes exactly one point.
std::vector<Piece> pieces_of_line(Piece from, Piece to, uint16_t max_step_um) {
  MotionRig rig;
  rig.start_at({double(from.x_um), double(from.y_um), 0});
  const int32_t at[3] = {from.x_um, from.y_um, 0};
  while (rig.ring.free_space() > 0) rig.planner.push(&rig.ring, at, 5000, 0, 0);
  core::Spline s{};
  s.degree = 1;
  s.control_count = 2;
  s.knot_count = 4;
  s.control[0] = {from.x_um, from.y_um, core::kWeightOneQ14};
  s.control[1] = {to.x_um, to.y_um, core::kWeightOneQ14};
  s.knot[2] = s.knot[3] = 1000;
  app::PointGenerator gen;
  gen.set_resolution(max_step_um, core::kDefaultChordToleranceUm);
  EXPECT_EQ(gen.begin(&s, 5000, 0, 1, 0, 0), core::GeometryError::kOk);
  const int32_t travel[2] = {1000000, 1000000};
  std::vector<Piece> out;
  for (long guard = 0; guard < 2000000; ++guard) {
    app::PlanEntry e;
    rig.ring.pop(&e);
    const app::GenStatus g = gen.run(&rig.planner, &rig.ring, travel, 8);
    // The machine position (no map: the planned one); last_um() moves once the whole chord
    // is pushed.
    const int32_t* last = rig.planner.machine_um();
    if (out.empty() || out.back().x_um != last[0] || out.back().y_um != last[1])
      out.push_back({last[0], last[1]});
    if (g != app::GenStatus::kMore) break;
  }
  return out;
}

TEST(PointGenerator, PiecesOfAChordStayOnItAtEveryStep) {
  const struct {
    Piece from, to;
  } lines[] = {
      {{10000, 20000}, {158770, 38270}},    // 150 mm at 7 degrees: 148 770 pieces at 1 um
      {{90000, 90000}, {82185, 108410}},    // 20 mm at 113 degrees
      {{120000, 150000}, {100463, 93286}},  // 60 mm at 251 degrees
      {{5000, 5000}, {5000 + 3001, 5000 + 2999}},
  };
  const uint16_t steps_um[] = {1, 3, 50, 1000, 65535};
  for (const auto& line : lines) {
    const double dx = line.to.x_um - line.from.x_um, dy = line.to.y_um - line.from.y_um;
    const double span = std::max(std::fabs(dx), std::fabs(dy));
    for (const uint16_t step : steps_um) {
      SCOPED_TRACE(testing::Message()
                   << "to " << line.to.x_um << "," << line.to.y_um << " step " << step);
      const std::vector<Piece> p = pieces_of_line(line.from, line.to, step);
      ASSERT_GE(p.size(), 2u);
      EXPECT_EQ(p.front().x_um, line.from.x_um);
      EXPECT_EQ(p.front().y_um, line.from.y_um);
      EXPECT_EQ(p.back().x_um, line.to.x_um);
      EXPECT_EQ(p.back().y_um, line.to.y_um);
      EXPECT_EQ(double(p.size() - 1), std::ceil(span / step));
      double worst_off = 0;
      long longest = 0;
      for (size_t k = 1; k < p.size(); ++k) {
        // Where piece k should end on the exact line: k / n of the way.
        const double f = double(k) / double(p.size() - 1);
        worst_off = std::max(worst_off, std::fabs(p[k].x_um - (line.from.x_um + f * dx)));
        worst_off = std::max(worst_off, std::fabs(p[k].y_um - (line.from.y_um + f * dy)));
        longest = std::max(longest, std::labs(long(p[k].x_um) - p[k - 1].x_um));
        longest = std::max(longest, std::labs(long(p[k].y_um) - p[k - 1].y_um));
      }
      EXPECT_LE(worst_off, 0.5 + 1e-9);
      EXPECT_LE(longest, long(step));
    }
  }
}

}  // namespace
}  // namespace fake_app
