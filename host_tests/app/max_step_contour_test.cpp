// Straight splines at every #U maximum step, on the TMC428 model: the point generator splits
// each chord of the curve walker into pieces of at most max_step, and the tool must stay on
// the line whatever the step, the direction, the degree and the feed (issue 22, item 2).
#include <gtest/gtest.h>

#include <cmath>   // std::cos, std::sin, std::lround
#include <cstdio>  // std::printf
#include <vector>  // std::vector

#include "firmware/app/point_generator.h"
#include "firmware/core/spline.h"
#include "host_tests/app/model_rig.h"
#include "host_tests/app/path_metrics.h"

namespace fake_app {
namespace {

const double kLineUm = 4000;  // long enough for a hundred pieces at 40 um

// A straight spline of the given degree from `from` along angle_deg: collinear control
// points spaced unevenly (so the parameter does not run at a constant speed along the
// line), rational with unit weights for the #Q line element's form.
core::Spline straight_spline(const P3& from, double angle_deg, int degree, bool rational) {
  const double fractions[] = {0.0, 0.15, 0.45, 0.6, 1.0};
  const int n = degree + 2;  // one knot inside: a joint on the line
  core::Spline s{};
  s.degree = uint8_t(degree);
  s.rational = rational;
  s.control_count = uint16_t(n);
  s.knot_count = uint16_t(n + degree + 1);
  const double a = angle_deg * M_PI / 180;
  for (int i = 0; i < n; ++i) {
    const double f = i == n - 1 ? 1.0 : fractions[i];
    s.control[i] = {int32_t(std::lround(from.x + f * kLineUm * std::cos(a))),
                    int32_t(std::lround(from.y + f * kLineUm * std::sin(a))), core::kWeightOneQ14};
  }
  for (int i = 0; i < n + degree + 1; ++i) s.knot[i] = i <= degree ? 0 : (i < n ? 700 : 2000);
  return s;
}

struct LineRun {
  bool finished;      // at the line's end, at rest
  double error_um;    // contour error of the tool's path against the straight line
  double time_ratio;  // time taken / (length / feed)
};

// Runs the spline through the point generator at max_step_um and feed on the TMC428 model.
LineRun run_line(const core::Spline& s, uint16_t max_step_um, uint16_t feed_um_s) {
  LineRun out = {false, 0, 0};
  ModelRig rig;
  if (!rig.setup()) return out;
  const P3 from = {double(s.control[0].x_um), double(s.control[0].y_um), 0};
  const P3 to = {double(s.control[s.control_count - 1].x_um),
                 double(s.control[s.control_count - 1].y_um), 0};
  rig.start_at(from);
  app::PointGenerator gen;
  gen.set_resolution(max_step_um, core::kDefaultChordToleranceUm);
  if (gen.begin(&s, feed_um_s, 0, 1, 0, 0) != core::GeometryError::kOk) return out;
  const int32_t travel[2] = {rig.scaling.travel_um[0], rig.scaling.travel_um[1]};
  bool generating = true;
  const double nominal_ms = kLineUm * 1000 / feed_um_s;
  const long max_ms = long(nominal_ms) * 4 + 2000;
  for (long i = 0; i < max_ms; ++i) {
    if (generating) {  // one background pass per millisecond
      const app::GenStatus g = gen.run(&rig.planner, &rig.ring, travel, 8);
      if (g == app::GenStatus::kFailed || g == app::GenStatus::kOutside) return out;
      generating = g == app::GenStatus::kMore;
    }
    rig.tick();
    const bool stopped = rig.chip.v_actual_q8(0) == 0 && rig.chip.v_actual_q8(1) == 0;
    if (!generating && rig.controller.finished() && stopped) {
      const P3& end = rig.samples.back();
      out.finished = std::hypot(end.x - to.x, end.y - to.y) <= 1.5;
      out.error_um = max_contour_error(rig.samples, {from, to});
      out.time_ratio = (i + 1) / nominal_ms;
      return out;
    }
  }
  return out;
}

TEST(MaxStepContour, StraightSplinesStayOnTheLineAtEveryStepDirectionDegreeAndFeed) {
  // From the smallest #U max_step to 2 mm; directions away from the axes and the diagonals
  // as well as on them; degrees 1-3 and the rational quadratic of a #Q line; three feeds.
  const uint16_t steps_um[] = {1, 10, 50, 200, 1000, 2000};
  const int kDirections = 12;
  const uint16_t feeds_um_s[] = {2000, 6000, 10000};
  const struct {
    int degree;
    bool rational;
  } kinds[] = {{1, false}, {2, false}, {3, false}, {2, true}};
  const P3 centre = {100000, 100000, 0};
  double worst = 0;
  for (const uint16_t step : steps_um) {
    double worst_step = 0;
    for (int d = 0; d < kDirections; ++d) {
      const double angle = 360.0 * d / kDirections + 7;  // 7, 37, 67 ... 337 degrees
      const P3 from = {centre.x - kLineUm / 2 * std::cos(angle * M_PI / 180),
                       centre.y - kLineUm / 2 * std::sin(angle * M_PI / 180), 0};
      for (const auto& kind : kinds) {
        const core::Spline s = straight_spline(from, angle, kind.degree, kind.rational);
        for (const uint16_t feed : feeds_um_s) {
          const LineRun r = run_line(s, step, feed);
          const std::string what =
              "step " + std::to_string(step) + " um, " + std::to_string(int(angle)) +
              " deg, degree " + std::to_string(kind.degree) + (kind.rational ? " rational" : "") +
              ", feed " + std::to_string(feed) + " um/s";
          EXPECT_TRUE(r.finished) << what;
          EXPECT_LE(r.error_um, 8.0) << what;
          // The pieces of a line meet without turns, so nothing slows the tool but the
          // start and the stop (and, at 1 um pieces, the tick's four targets per
          // millisecond: about 4 mm/s).
          const double ideal = std::max(1.0, feed / 4000.0);
          EXPECT_LE(r.time_ratio, 1.35 * ideal) << what;
          const double err = r.error_um;
          worst_step = std::max(worst_step, err);
        }
      }
    }
    std::printf("[ metrics  ] max_step %5u um: contour error at most %5.2f um\n", step, worst_step);
    worst = std::max(worst, worst_step);
  }
  std::printf("[ metrics  ] straight splines, every step: contour error at most %.2f um\n", worst);
}

}  // namespace
}  // namespace fake_app
