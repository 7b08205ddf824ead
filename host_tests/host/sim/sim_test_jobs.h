// Small drawings and helpers for the simulated-machine tests.
#ifndef HOST_TESTS_HOST_SIM_SIM_TEST_JOBS_H
#define HOST_TESTS_HOST_SIM_SIM_TEST_JOBS_H

#include <atomic>  // std::atomic
#include <cmath>   // std::sqrt
#include <thread>  // std::thread

#include "host/lib/sim/sim_server.h"

#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_plan.h"

namespace host::test {

// A full circle of radius r_mm around (cx, cy) as one rational quadratic B-spline
// (four 90-degree arcs, weights 1, sqrt(2)/2).
inline Curve circle_curve(double cx, double cy, double r_mm) {
  const double w = std::sqrt(0.5);
  Curve c;
  BSpline s;
  c.kind = "CIRCLE";
  c.source = "test circle";
  s.degree = 2;
  const double px[] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
  const double py[] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  for (int i = 0; i < 9; ++i) {
    s.control.push_back(Point2(cx + r_mm * px[i], cy + r_mm * py[i]));
    s.weights.push_back(i % 2 ? w : 1.0);
  }
  s.knots = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
  c.set_spline(s);
  return c;
}

// A straight line as a degree-1 B-spline.
inline Curve line_curve(double x0, double y0, double x1, double y1) {
  Curve c;
  BSpline s;
  c.kind = "LINE";
  c.source = "test line";
  s.degree = 1;
  s.control = {Point2(x0, y0), Point2(x1, y1)};
  s.knots = {0, 0, 1, 1};
  c.set_spline(s);
  return c;
}

// A cubic S-curve with an interior knot.
inline Curve s_curve(double x0, double y0) {
  Curve c;
  BSpline s;
  c.kind = "SPLINE";
  c.source = "test S-curve";
  s.degree = 3;
  s.control = {Point2(x0, y0), Point2(x0 + 5, y0 + 10), Point2(x0 + 10, y0 - 10),
               Point2(x0 + 15, y0 + 10), Point2(x0 + 20, y0)};
  s.knots = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  c.set_spline(s);
  return c;
}

inline Drawing drawing_of(std::vector<Curve> curves) {
  Drawing d;
  d.path = "test.dxf";
  d.format = "DXF";
  d.units = "mm";
  d.curves = std::move(curves);
  return d;
}

// n separate short lines in a row, planned in that order: four commands each (pen up, rapid,
// pen down, feed), a long command list for a short drawing. z_up_mm: short pen lifts make a
// short job in machine time.
inline JobPlan separate_lines(int n, double z_up_mm = PlanOptions().z_up_mm) {
  std::vector<Curve> curves;
  for (int i = 0; i < n; ++i) {
    const double x = 10 + (i % 40) * 2.0, y = 10 + (i / 40) * 2.0;
    curves.push_back(line_curve(x, y, x + 0.5, y));
  }
  PlanOptions o;
  o.reorder = false;
  o.z_up_mm = z_up_mm;
  return plan_job(drawing_of(std::move(curves)), o);
}

inline JobPlan plan_of(const Drawing& d, double feed_mm_s = 10.0) {
  PlanOptions o;
  o.feed_mm_per_s = feed_mm_s;
  o.margin_mm = 5.0;
  return plan_job(d, o);
}

// Serves a simulator from a thread for the lifetime of the object; stop() or the
// destructor ends and joins it, so a failing assertion cannot leave the thread running.
class Serving {
 public:
  explicit Serving(sim::SimServer& server) : thread_([this, &server] { server.run(stop_); }) {}
  ~Serving() { stop(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace host::test

#endif  // HOST_TESTS_HOST_SIM_SIM_TEST_JOBS_H
