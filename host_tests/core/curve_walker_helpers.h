// Test helpers for CurveWalker: run it to completion, measure chord errors against Eigen.
#ifndef HOST_TESTS_CORE_CURVE_WALKER_HELPERS_H
#define HOST_TESTS_CORE_CURVE_WALKER_HELPERS_H

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

#include "firmware/core/curve_walker.h"
#include "host_tests/core/spline_reference.h"

namespace stepping {

struct Emitted {
  core::PointUm p;
  int span;
  double t;  // 0..1 in the span
};

struct Run {
  core::GeometryError begin_error;
  core::GeometryError end_error;
  std::vector<Emitted> points;
};

// Runs a walker over s; stops after max_points (a runaway guard for the test).
inline Run run(const core::Spline& s, const core::StepSettings& st, size_t max_points = 200000) {
  core::CurveWalker walker;
  Run r;
  r.begin_error = walker.begin(&s, st);
  core::PointUm p;
  while (r.points.size() < max_points && walker.next(&p)) {
    r.points.push_back({p, walker.span(), walker.t_q16() / 65536.0});
  }
  r.end_error = walker.error();
  return r;
}

// The reference curve at n points per non-empty span (t = k / n), rounded to whole
// micrometres: uniform stepping, for comparison with the walker's adaptive steps.
inline Run uniform_reference(const core::Spline& s, int n) {
  Run r;
  r.begin_error = r.end_error = core::GeometryError::kOk;
  bool first = true;
  for (int span = s.degree; span < s.control_count; ++span) {
    if (s.knot[span + 1] <= s.knot[span]) continue;
    for (int k = first ? 0 : 1; k <= n; ++k) {
      const double t = (double)k / n;
      const Eigen::Vector2d q = reference::span_point(s, span, t);
      r.points.push_back({{(int32_t)std::lround(q.x()), (int32_t)std::lround(q.y())}, span, t});
    }
    first = false;
  }
  return r;
}

inline core::StepSettings adaptive(int tol_um, int offset_um = 0) {
  core::StepSettings st = core::default_step_settings();
  st.mode = core::StepMode::kAdaptive;
  st.chord_tolerance_um = (uint16_t)tol_um;
  st.tool_offset_um = offset_um;
  return st;
}

// Distance from q to segment ab.
inline double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& q) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  double s = len2 > 0 ? (q - a).dot(ab) / len2 : 0;
  s = std::min(1.0, std::max(0.0, s));
  return (a + s * ab - q).norm();
}

inline Eigen::Vector2d vec(const core::PointUm& p) {
  return Eigen::Vector2d(p.x_um, p.y_um);
}

// Real chord error of a run without offset: the true curve (Eigen) sampled densely between
// the parameters of consecutive points, distance to the straight segment between them.
inline double max_chord_error_um(const core::Spline& s, const Run& r, int samples = 64) {
  const reference::Curve curve(s);
  double worst = 0;
  for (size_t i = 1; i < r.points.size(); ++i) {
    const Emitted& a = r.points[i - 1];
    const Emitted& b = r.points[i];
    const double ua = reference::span_u(s, a.span, a.t);
    const double ub = reference::span_u(s, b.span, b.t);
    for (int k = 1; k < samples; ++k) {
      const double u = ua + (ub - ua) * k / samples;
      const Eigen::Vector2d q = curve.at(u);
      worst = std::max(worst, segment_distance(vec(a.p), vec(b.p), q));
    }
  }
  return worst;
}

}  // namespace stepping

#endif  // HOST_TESTS_CORE_CURVE_WALKER_HELPERS_H
