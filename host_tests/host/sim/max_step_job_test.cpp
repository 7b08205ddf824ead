// A job sent with a small #U maximum step, as a client other than `engraver send` may (the
// protocol's example is 50 um): diagonal lines (#Q line elements), arcs and a cubic through
// the whole chain (encoder, frames, the firmware on the TMC428 model) stay on their curves as
// closely as at the sender's own 1 mm step (issue 22, item 2).
#include <gtest/gtest.h>

#include <cstdio>  // std::printf

#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using test::circle_curve;
using test::drawing_of;
using test::plan_of;
using test::s_curve;

// A polyline of diagonal lines: one degree-1 curve, which goes out as #Q line elements (a
// single straight line would be a #G, which the point generator does not split).
Curve zigzag_polyline() {
  Curve c;
  BSpline s;
  c.kind = "LWPOLYLINE";
  c.source = "test zigzag";
  s.degree = 1;
  s.control = {Point2(0, 0), Point2(40, 9.3), Point2(80, 1.7), Point2(110, 33.1), Point2(60, 41.9)};
  s.knots = {0, 0, 1, 2, 3, 4, 4};
  c.set_spline(s);
  return c;
}

TEST(MaxStepJob, SmallStepsKeepTheToolOnLinesArcsAndCubics) {
  const JobPlan plan =
      plan_of(drawing_of({zigzag_polyline(), circle_curve(20, 30, 6), s_curve(40, 20)}), 6.0);
  for (const uint16_t step_um : {1, 10, 50, 1000}) {
    sim::SimJobOptions o;
    o.sender.status_interval = std::chrono::milliseconds(2);
    o.encode.max_step_um = step_um;
    const sim::SimJobResult r = sim::run_sim_job(plan, o);
    ASSERT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
    std::printf("[ metrics  ] #U %4u um: max contour error %.1f um at (%.3f, %.3f) mm\n", step_um,
                r.max_contour_error_um, r.worst_contour_sample.x_mm, r.worst_contour_sample.y_mm);
    // The planned points lie within the chord tolerance (5 um) of the curves; the tick's
    // path error on a straight piece is under 2 um (MaxStepContour on the TMC428 model).
    EXPECT_LE(r.max_contour_error_um, 8.0) << "#U " << step_um << " um";
  }
}

}  // namespace
}  // namespace host
