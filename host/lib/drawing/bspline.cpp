// B-spline operations in double precision: checks, De Boor, reversal, knot insertion,
// clamping, Bezier decomposition, affine maps, tolerance-driven sampling, extents.
#include "host/lib/drawing/bspline.h"

#include <algorithm>  // std::reverse, std::upper_bound
#include <cmath>      // std::isfinite, std::fabs
#include <sstream>    // std::ostringstream

namespace host {

std::string check_bspline(const BSpline& s) {
  std::ostringstream e;
  const size_t n = s.control.size();
  if (s.degree < 1) {
    e << "degree " << s.degree << " (must be at least 1)";
  } else if (n < static_cast<size_t>(s.degree) + 1) {
    e << n << " control points for degree " << s.degree << " (need at least " << s.degree + 1
      << ")";
  } else if (s.knots.size() != n + s.degree + 1) {
    e << s.knots.size() << " knots for " << n << " control points of degree " << s.degree
      << " (need " << n + s.degree + 1 << ")";
  } else if (!s.weights.empty() && s.weights.size() != n) {
    e << s.weights.size() << " weights for " << n << " control points";
  }
  if (!e.str().empty()) return e.str();
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s.control[i].x()) || !std::isfinite(s.control[i].y())) {
      e << "control point " << i << " is not a finite number";
      return e.str();
    }
    if (!s.weights.empty() && !(std::isfinite(s.weights[i]) && s.weights[i] > 0)) {
      e << "weight " << i << " is " << s.weights[i] << " (weights must be positive)";
      return e.str();
    }
  }
  for (size_t i = 0; i < s.knots.size(); ++i) {
    if (!std::isfinite(s.knots[i])) {
      e << "knot " << i << " is not a finite number";
      return e.str();
    }
    if (i > 0 && s.knots[i] < s.knots[i - 1]) {
      e << "knots decrease at index " << i << " (" << s.knots[i - 1] << " then " << s.knots[i]
        << ")";
      return e.str();
    }
  }
  if (!(s.t_max() > s.t_min())) {
    e << "empty parameter range (knot " << s.degree << " == knot " << n << " == " << s.t_min()
      << ")";
    return e.str();
  }
  return std::string();
}

namespace {

// Index k of the span [knots[k], knots[k+1]) holding t, within degree..n-1.
size_t find_span(const BSpline& s, double t) {
  const size_t n = s.control.size();
  if (t >= s.t_max()) {
    size_t k = n - 1;
    while (k > static_cast<size_t>(s.degree) && !(s.knots[k + 1] > s.knots[k])) --k;
    return k;
  }
  auto it = std::upper_bound(s.knots.begin() + s.degree, s.knots.begin() + n, t);
  return static_cast<size_t>(it - s.knots.begin()) - 1;
}

}  // namespace

Point2 evaluate(const BSpline& s, double t) {
  t = std::min(std::max(t, s.t_min()), s.t_max());
  const int p = s.degree;
  const size_t k = find_span(s, t);
  // Homogeneous De Boor: (w x, w y, w), on the stack for the usual degrees (sampling
  // evaluates millions of points; a heap block each cost as much as the arithmetic).
  const int kOnStack = 8;
  Eigen::Vector3d stack[kOnStack];
  std::vector<Eigen::Vector3d> heap;
  if (p + 1 > kOnStack) heap.resize(static_cast<size_t>(p) + 1);
  Eigen::Vector3d* d = p + 1 > kOnStack ? heap.data() : stack;
  for (int j = 0; j <= p; ++j) {
    const size_t i = k - p + j;
    const double w = s.weight(i);
    d[j] = Eigen::Vector3d(s.control[i].x() * w, s.control[i].y() * w, w);
  }
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const size_t i = k - p + j;
      const double den = s.knots[i + p - r + 1] - s.knots[i];
      const double a = den > 0 ? (t - s.knots[i]) / den : 0.0;
      d[j] = (1.0 - a) * d[j - 1] + a * d[j];
    }
  }
  return Point2(d[p].x() / d[p].z(), d[p].y() / d[p].z());
}

BSpline reversed(const BSpline& s) {
  BSpline r = s;
  std::reverse(r.control.begin(), r.control.end());
  std::reverse(r.weights.begin(), r.weights.end());
  std::reverse(r.knots.begin(), r.knots.end());
  for (double& k : r.knots) k = -k;
  return r;
}

BSpline insert_knot(const BSpline& s, double u) {
  const int p = s.degree;
  const size_t n = s.control.size();
  const size_t k = find_span(s, u);
  BSpline r;
  r.degree = p;
  r.knots = s.knots;
  r.knots.insert(r.knots.begin() + k + 1, u);
  std::vector<Eigen::Vector3d> h(n);
  for (size_t i = 0; i < n; ++i) {
    const double w = s.weight(i);
    h[i] = Eigen::Vector3d(s.control[i].x() * w, s.control[i].y() * w, w);
  }
  std::vector<Eigen::Vector3d> q(n + 1);
  for (size_t i = 0; i <= n; ++i) {
    if (i + p <= k) {
      q[i] = h[i];
    } else if (i > k) {
      q[i] = h[i - 1];
    } else {
      const double den = s.knots[i + p] - s.knots[i];
      const double a = den > 0 ? (u - s.knots[i]) / den : 0.0;
      q[i] = (1.0 - a) * h[i - 1] + a * h[i];
    }
  }
  r.control.resize(n + 1);
  if (s.rational()) r.weights.resize(n + 1);
  for (size_t i = 0; i <= n; ++i) {
    r.control[i] = Point2(q[i].x() / q[i].z(), q[i].y() / q[i].z());
    if (s.rational()) r.weights[i] = q[i].z();
  }
  return r;
}

namespace {

// Multiplicity of value u in the knot vector.
int multiplicity(const BSpline& s, double u) {
  int m = 0;
  for (double k : s.knots) m += (k == u) ? 1 : 0;
  return m;
}

// Drops the first `front` and last `back` control points (and knots), used after
// clamping to remove the part outside the valid range.
BSpline trim(const BSpline& s, size_t front, size_t back) {
  BSpline r;
  r.degree = s.degree;
  r.control.assign(s.control.begin() + front, s.control.end() - back);
  if (s.rational()) r.weights.assign(s.weights.begin() + front, s.weights.end() - back);
  r.knots.assign(s.knots.begin() + front, s.knots.end() - back);
  return r;
}

}  // namespace

BSpline clamped(const BSpline& s) {
  const int p = s.degree;
  BSpline r = s;
  const double a = s.t_min();
  const double b = s.t_max();
  // Raise the multiplicity of a and b to p (a p+1-th copy would add nothing inside).
  while (multiplicity(r, a) < p) r = insert_knot(r, a);
  while (multiplicity(r, b) < p) r = insert_knot(r, b);
  // Now the knots before the first a and after the last b belong to control points that
  // no longer influence [a, b]: keep exactly one a and one b outside the p inner copies.
  size_t first_a = 0;
  while (r.knots[first_a] < a) ++first_a;
  size_t last_b = r.knots.size() - 1;
  while (r.knots[last_b] > b) --last_b;
  // Index of the first of the p copies of a that are followed by the curve's first point.
  const size_t count_a = static_cast<size_t>(multiplicity(r, a));
  const size_t count_b = static_cast<size_t>(multiplicity(r, b));
  // With the run of a ending at index e, the curve starts at control point e - p; with the
  // run of b starting at index sb, it ends at control point sb - 1 (knots up to sb + p).
  const size_t front = first_a + count_a - 1 - p;
  const size_t last_knot = last_b - count_b + 1 + p;
  const size_t back = r.knots.size() - 1 - last_knot;
  BSpline t = trim(r, front, back);
  t.knots.front() = a;
  t.knots.back() = b;
  return t;
}

std::vector<BSpline> bezier_pieces(const BSpline& s) {
  BSpline r = clamped(s);
  const int p = r.degree;
  // Raise every interior knot to multiplicity p.
  std::vector<double> interior;
  for (size_t i = p + 1; i < r.control.size(); ++i) {
    if (interior.empty() || interior.back() != r.knots[i]) interior.push_back(r.knots[i]);
  }
  for (double u : interior) {
    while (multiplicity(r, u) < p) r = insert_knot(r, u);
  }
  std::vector<BSpline> out;
  for (size_t first = 0; first + p < r.control.size(); first += p) {
    BSpline b;
    b.degree = p;
    b.control.assign(r.control.begin() + first, r.control.begin() + first + p + 1);
    if (r.rational())
      b.weights.assign(r.weights.begin() + first, r.weights.begin() + first + p + 1);
    const double ka = r.knots[first + p];
    const double kb = r.knots[first + p + 1];
    b.knots.assign(p + 1, ka);
    b.knots.insert(b.knots.end(), p + 1, kb);
    if (kb > ka) out.push_back(b);
  }
  return out;
}

Point2 start_point(const BSpline& s) {
  return evaluate(s, s.t_min());
}
Point2 end_point(const BSpline& s) {
  return evaluate(s, s.t_max());
}

BSpline transformed(const BSpline& s, const Eigen::Matrix2d& a, const Point2& b) {
  BSpline r = s;
  for (Point2& c : r.control) c = a * c + b;
  return r;
}

namespace {

// Points after p0 up to p1 (the curve at t0 and t1; pm at the middle tm) until the curve's
// points at a quarter, the middle and three quarters lie within tol of the chord. The
// quarters are the halves' middles: each point is evaluated once however often the piece
// is split (evaluating was most of sampling).
void subdivide(const BSpline& s, double t0, const Point2& p0, double tm, const Point2& pm,
               double t1, const Point2& p1, double tol, int depth, std::vector<Point2>& out) {
  if (depth >= 24) {
    out.push_back(p1);
    return;
  }
  const double ta = 0.5 * (t0 + tm), tb = 0.5 * (tm + t1);
  const Point2 pa = evaluate(s, ta), pb = evaluate(s, tb);
  const Point2 d = p1 - p0;
  const double len = d.norm();
  auto near_chord = [&](const Point2& q) {
    const double dist =
        len > 0 ? std::fabs(d.x() * (q - p0).y() - d.y() * (q - p0).x()) / len : (q - p0).norm();
    // Also bound the distance along the chord (a curve that doubles back).
    const double along = len > 0 ? (q - p0).dot(d) / len : 0.0;
    return !(dist > tol || along < -tol || along > len + tol);
  };
  if (near_chord(pa) && near_chord(pm) && near_chord(pb)) {
    out.push_back(p1);
    return;
  }
  subdivide(s, t0, p0, ta, pa, tm, pm, tol, depth + 1, out);
  subdivide(s, tm, pm, tb, pb, t1, p1, tol, depth + 1, out);
}

}  // namespace

std::vector<Point2> sample(const BSpline& s, double tol_mm) {
  std::vector<Point2> out;
  out.push_back(start_point(s));
  const size_t n = s.control.size();
  for (size_t k = s.degree; k < n; ++k) {
    const double t0 = s.knots[k];
    const double t1 = s.knots[k + 1];
    if (!(t1 > t0)) continue;
    // At least a few pieces per span so that a closed span is not mistaken for a point.
    const int pieces = 4;
    for (int i = 0; i < pieces; ++i) {
      const double a = t0 + (t1 - t0) * i / pieces;
      const double b = t0 + (t1 - t0) * (i + 1) / pieces;
      const double m = 0.5 * (a + b);
      subdivide(s, a, evaluate(s, a), m, evaluate(s, m), b, evaluate(s, b), tol_mm, 0, out);
    }
  }
  return out;
}

namespace {

// The Bezier piece of span k (knots[k] < knots[k+1]) from the p+1 control points and 2p+2
// knots that define it alone: clamping that local spline costs O(p^2), whatever the
// curve's length.
BSpline span_bezier(const BSpline& s, size_t k) {
  const size_t p = static_cast<size_t>(s.degree);
  BSpline local;
  local.degree = s.degree;
  local.control.assign(s.control.begin() + (k - p), s.control.begin() + (k + 1));
  if (s.rational()) local.weights.assign(s.weights.begin() + (k - p), s.weights.begin() + (k + 1));
  local.knots.assign(s.knots.begin() + (k - p), s.knots.begin() + (k + p + 2));
  return clamped(local);
}

typedef std::vector<Eigen::Vector3d> Homogeneous;  // (w x, w y, w) per control point

bool hull_within(const Homogeneous& h, const Extents& e, double tol) {
  for (const Eigen::Vector3d& q : h) {
    const double x = q.x() / q.z();
    const double y = q.y() / q.z();
    if (x < e.min.x() - tol || x > e.max.x() + tol || y < e.min.y() - tol || y > e.max.y() + tol)
      return false;
  }
  return true;
}

// Grows e until the piece lies within e widened by tol. A Bezier piece with positive
// weights lies in the hull of its control points, so a piece whose hull is already inside
// is done; otherwise it is halved (De Casteljau) and its midpoint, a point of the curve,
// is added. Only pieces at an extreme are halved, so the cost is about the depth per
// extreme, not the curve's length over tol.
void grow_extents(const Homogeneous& h, double tol, int depth, Extents& e) {
  if (depth >= 64 || hull_within(h, e, tol)) return;
  const size_t n = h.size();
  Homogeneous left(n);
  Homogeneous right(n);
  Homogeneous d = h;
  for (size_t r = 0; r < n; ++r) {
    left[r] = d[0];
    right[n - 1 - r] = d[n - 1 - r];
    for (size_t j = 0; j + r + 1 < n; ++j) d[j] = 0.5 * (d[j] + d[j + 1]);
  }
  const Eigen::Vector3d& mid = left[n - 1];
  e.add(Point2(mid.x() / mid.z(), mid.y() / mid.z()));
  grow_extents(left, tol, depth + 1, e);
  grow_extents(right, tol, depth + 1, e);
}

}  // namespace

Extents curve_extents(const BSpline& s) {
  // Exact to 1 nm, or to 1e-12 of the control polygon's size for curves beyond 1 km.
  Extents hull;
  for (const Point2& c : s.control) hull.add(c);
  const double tol = std::max(1e-6, 1e-12 * std::max(hull.width(), hull.height()));
  // The curve's points at its knots first, so that most pieces' hulls are already inside.
  Extents e;
  e.add(start_point(s));
  for (size_t k = static_cast<size_t>(s.degree) + 1; k < s.control.size(); ++k)
    e.add(evaluate(s, s.knots[k]));
  e.add(end_point(s));
  for (size_t k = static_cast<size_t>(s.degree); k < s.control.size(); ++k) {
    if (!(s.knots[k + 1] > s.knots[k])) continue;
    const BSpline b = span_bezier(s, k);
    Homogeneous h(b.control.size());
    for (size_t i = 0; i < h.size(); ++i) {
      const double w = b.weight(i);
      h[i] = Eigen::Vector3d(b.control[i].x() * w, b.control[i].y() * w, w);
    }
    grow_extents(h, tol, 0, e);
  }
  return e;
}

}  // namespace host
