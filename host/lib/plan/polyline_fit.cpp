// Least-squares cubic B-spline fits of polyline runs; see polyline_fit.h.
#include "host/lib/plan/polyline_fit.h"

#include <Eigen/Dense>  // least squares

#include <algorithm>  // std::min, std::max
#include <cmath>      // std::acos, std::floor

#include "host/lib/drawing/conics.h"

namespace host {

namespace {

const double kPi = 3.14159265358979323846;

// The degree-3 basis functions of a clamped knot vector at t (NURBS Book A2.2), all m.
std::vector<double> basis(const std::vector<double>& u, int m, double t) {
  const int p = 3;
  int k = p;
  while (k < m - 1 && t >= u[k + 1]) ++k;
  double n[p + 1] = {1, 0, 0, 0}, left[p + 1], right[p + 1];
  for (int j = 1; j <= p; ++j) {
    left[j] = t - u[k + 1 - j];
    right[j] = u[k + j] - t;
    double saved = 0;
    for (int r = 0; r < j; ++r) {
      const double d = right[r + 1] + left[j - r];
      const double tmp = d > 0 ? n[r] / d : 0;
      n[r] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    n[j] = saved;
  }
  std::vector<double> all(m, 0.0);
  for (int j = 0; j <= p; ++j) all[k - p + j] = n[j];
  return all;
}

double distance_to_segment(const Point2& q, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::max(0.0, std::min(1.0, (q - a).dot(ab) / len2)) : 0.0;
  return (q - (a + s * ab)).norm();
}

// A clamped cubic through the run's ends with m control points fitted to the rest, or an
// empty spline when it is not within tolerance.
BSpline fit_run(const std::vector<Point2>& p, const std::vector<double>& t, int m, double tol) {
  const int n = static_cast<int>(p.size()) - 1;  // segments
  BSpline s;
  s.degree = 3;
  s.knots.assign(4, 0.0);
  // Interior knots at quantiles of the data parameters: every span holds data.
  for (int j = 1; j <= m - 4; ++j) {
    const double pos = static_cast<double>(j) * n / (m - 3);
    const int i = static_cast<int>(std::floor(pos));
    s.knots.push_back(t[i] + (pos - i) * (t[std::min(i + 1, n)] - t[i]));
  }
  s.knots.insert(s.knots.end(), 4, 1.0);
  for (size_t k = 1; k < s.knots.size(); ++k)
    if (s.knots[k] <= s.knots[k - 1] && k > 3 && k < s.knots.size() - 4) return BSpline();
  Eigen::MatrixXd a(n - 1, m - 2);
  Eigen::MatrixXd b(n - 1, 2);
  for (int i = 1; i < n; ++i) {
    const std::vector<double> nb = basis(s.knots, m, t[i]);
    for (int j = 1; j < m - 1; ++j) a(i - 1, j - 1) = nb[j];
    const Point2 r = p[i] - nb[0] * p[0] - nb[m - 1] * p[n];
    b(i - 1, 0) = r.x();
    b(i - 1, 1) = r.y();
  }
  const Eigen::MatrixXd q = a.colPivHouseholderQr().solve(b);
  s.control.push_back(p[0]);
  for (int j = 0; j < m - 2; ++j) s.control.push_back(Point2(q(j, 0), q(j, 1)));
  s.control.push_back(p[n]);
  for (const Point2& c : s.control)
    if (!std::isfinite(c.x()) || !std::isfinite(c.y())) return BSpline();
  // Vertices to the curve, and the curve (8 points per segment) to the segment it stands for.
  for (int i = 0; i <= n; ++i) {
    if ((evaluate(s, t[i]) - p[i]).norm() > tol) return BSpline();
    if (i == n) break;
    for (int k = 1; k < 8; ++k) {
      const Point2 c = evaluate(s, t[i] + (t[i + 1] - t[i]) * k / 8.0);
      if (distance_to_segment(c, p[i], p[i + 1]) > tol) return BSpline();
    }
  }
  return s;
}

// The fewest control points (4 upwards) that fit the run, or an empty spline.
BSpline fit(const std::vector<Point2>& p, const FitOptions& o) {
  const int n = static_cast<int>(p.size()) - 1;
  std::vector<double> t(1, 0.0);
  for (int i = 1; i <= n; ++i) t.push_back(t.back() + (p[i] - p[i - 1]).norm());
  for (double& v : t) v /= t.back();
  const int limit = std::min(o.max_control_points, n - 1);  // fewer than the segments
  for (int m = 4; m <= limit; m += std::max(1, m / 4)) {
    BSpline s = fit_run(p, t, m, o.tolerance_mm);
    if (!s.control.empty()) return s;
  }
  return BSpline();
}

BSpline straight(const std::vector<Point2>& p) {
  std::vector<BulgeVertex> v(p.size());
  for (size_t i = 0; i < p.size(); ++i) v[i].p = p[i];
  return polyline_spline(v, false);
}

}  // namespace

std::vector<BSpline> fit_polyline(const std::vector<Point2>& in, const FitOptions& o) {
  std::vector<Point2> p;
  for (const Point2& q : in)
    if (p.empty() || (q - p.back()).norm() > 1e-9) p.push_back(q);
  std::vector<BSpline> out;
  if (p.size() < 2) return out;
  const double cos_corner = std::cos(o.corner_deg * kPi / 180.0);
  // A vertex is a break when a segment next to it is long or the path turns sharply there.
  const size_t n = p.size() - 1;
  std::vector<bool> brk(p.size(), false);
  brk[0] = brk[n] = true;
  for (size_t i = 1; i < n; ++i) {
    const Point2 a = p[i] - p[i - 1], b = p[i + 1] - p[i];
    brk[i] = a.norm() > o.max_segment_mm || b.norm() > o.max_segment_mm ||
             a.dot(b) < cos_corner * a.norm() * b.norm();
  }
  std::vector<Point2> pending(1, p[0]);  // straight segments not yet emitted
  auto emit_straight = [&]() {
    if (pending.size() >= 2) out.push_back(straight(pending));
    pending.assign(1, pending.back());
  };
  size_t i = 0;
  while (i < n) {
    // The run of short segments from i to the next break (at most 2 * max control points).
    size_t j = i + 1;
    while (j < n && !brk[j] && j - i < static_cast<size_t>(2 * o.max_control_points)) ++j;
    const bool short_run = (p[i + 1] - p[i]).norm() <= o.max_segment_mm;
    BSpline s;
    if (short_run && static_cast<int>(j - i) >= o.min_segments) {
      s = fit(std::vector<Point2>(p.begin() + i, p.begin() + j + 1), o);
    }
    if (!s.control.empty()) {
      emit_straight();
      out.push_back(s);
      pending.assign(1, p[j]);
    } else {
      pending.insert(pending.end(), p.begin() + i + 1, p.begin() + j + 1);
    }
    i = j;
  }
  emit_straight();
  return out;
}

}  // namespace host
