// Polyline -> lines, exact arcs and fitted cubics (see contour_fit.h).
#include "host/lib/pcb/contour_fit.h"

#include <Eigen/Dense>  // normal equations of the cubic fit (LDLT)

#include <algorithm>  // std::max, std::rotate
#include <cmath>      // std::atan2, std::cos, std::ceil

namespace host::pcb {

namespace {

const double kPi = 3.14159265358979323846;

struct Primitive {
  enum Kind { kLine, kArc, kCubic } kind = kLine;
  size_t from = 0, to = 0;  // vertex indices
  Point2 centre{0, 0};      // kArc
  double radius = 0;        // kArc
  double sweep = 0;         // kArc: signed angle, counter-clockwise positive
  BSpline cubic;            // kCubic
};

double cross(const Point2& a, const Point2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Circle through three points; false when they are (nearly) collinear.
bool circle_through(const Point2& a, const Point2& b, const Point2& c, Point2* centre,
                    double* radius) {
  const Point2 ab = b - a, ac = c - a;
  const double d = 2 * cross(ab, ac);
  if (std::fabs(d) < 1e-18) return false;
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  const Point2 off((ac.y() * ab2 - ab.y() * ac2) / d, (ab.x() * ac2 - ac.x() * ab2) / d);
  *centre = a + off;
  *radius = off.norm();
  return true;
}

// atan(x) for 0 <= x <= 1 within kAtanError rad (1.51e-3 at worst): enough to tell most
// arcs from more than a full turn without an atan2 per chord.
const double kAtanError = 0.002;
double atan_roughly(double x) {
  return x * (kPi / 4 + (1 - x) * (0.2447 + 0.0663 * x));
}

// The arc's signed sweep from its vertices, chord by chord (counter-clockwise positive).
double arc_sweep(const std::vector<Point2>& p, size_t i, size_t j, const Point2& c) {
  double sweep = 0;
  for (size_t k = i; k < j; ++k)
    sweep += std::atan2(cross(p[k] - c, p[k + 1] - c), (p[k] - c).dot(p[k + 1] - c));
  return sweep;
}

// Whether vertices i..j lie on one circle within tol, turning one way in chords of at most
// 45 degrees and at most one full turn in all; out->sweep is left for arc_sweep (the
// greedy search tries every longer arc, and an atan2 per chord per try was a tenth of a
// board's time).
bool fits_arc(const std::vector<Point2>& p, size_t i, size_t j, double tol, Primitive* out) {
  Point2 c;
  double r;
  if (!circle_through(p[i], p[(i + j) / 2], p[j], &c, &r)) return false;
  if (r > 1000.0 || r < tol) return false;
  double turn_roughly = 0;
  int sign = 0;
  for (size_t k = i; k < j; ++k) {
    if (std::fabs((p[k] - c).norm() - r) > tol) return false;
    // A chord is the flattened arc: the arc bows off it by the sagitta, which must stay
    // within the tolerance too (an octagon's corners lie on a circle, but it is no circle;
    // and an arc bowing 3x the tolerance off its chords took isolation paths 6.7 um toward
    // the copper). 1 % more for the nanometre rounding of Clipper's vertices: where two of
    // its round joins meet, the chord's sagitta is twice its arc tolerance, 2.004 um for 1.
    const double chord2 = (p[k + 1] - p[k]).squaredNorm();
    if (chord2 / (8 * r) > 1.01 * tol) return false;
    // Within 45 degrees: the dot product positive and at least the cross product.
    const double cr = cross(p[k] - c, p[k + 1] - c), dot = (p[k] - c).dot(p[k + 1] - c);
    if (!(dot > 0) || std::fabs(cr) > dot) return false;
    const int s = cr > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
    turn_roughly += atan_roughly(std::fabs(cr) / dot);
  }
  const double full_turn = 2 * kPi + 1e-9;
  const double slack = static_cast<double>(j - i) * kAtanError;
  if (turn_roughly > full_turn + slack) return false;
  if (turn_roughly >= full_turn - slack && std::fabs(arc_sweep(p, i, j, c)) > full_turn)
    return false;
  out->kind = Primitive::kArc;
  out->from = i;
  out->to = j;
  out->centre = c;
  out->radius = r;
  return true;
}

// Cox-de Boor: the degree-3 basis functions at t (span found by linear search).
void cubic_basis(const std::vector<double>& knots, size_t n_control, double t,
                 std::vector<double>* n) {
  n->assign(n_control, 0.0);
  const int p = 3;
  size_t span = p;
  while (span + 1 < n_control && t >= knots[span + 1]) ++span;
  std::vector<double> left(p + 1), right(p + 1), b(p + 1);
  b[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = b[r] / (right[r + 1] + left[j - r]);
      b[r] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    b[j] = saved;
  }
  for (int j = 0; j <= p; ++j) (*n)[span - p + j] = b[j];
}

// Least-squares clamped cubic with n_cp control points (uniform knots on the chord-length
// parameters t, ends fixed); true when within tol of q and of the chord midpoints.
bool try_cubic(const std::vector<Point2>& q, const std::vector<double>& t, size_t n_cp, double tol,
               BSpline* out) {
  const size_t m = q.size();
  BSpline s;
  s.degree = 3;
  s.knots.assign(4, 0.0);
  for (size_t k = 1; k + 3 < n_cp; ++k) s.knots.push_back(static_cast<double>(k) / (n_cp - 3));
  s.knots.insert(s.knots.end(), 4, 1.0);
  Eigen::MatrixXd ata = Eigen::MatrixXd::Zero(n_cp - 2, n_cp - 2);
  Eigen::MatrixXd atb = Eigen::MatrixXd::Zero(n_cp - 2, 2);
  std::vector<double> basis;
  for (size_t k = 0; k < m; ++k) {
    cubic_basis(s.knots, n_cp, std::min(t[k], 1.0 - 1e-12), &basis);
    if (k + 1 == m) basis.assign(n_cp, 0.0), basis[n_cp - 1] = 1.0;
    const Point2 r = q[k] - basis[0] * q.front() - basis[n_cp - 1] * q.back();
    size_t nz[4], n_nz = 0;  // at most degree + 1 basis functions are non-zero
    for (size_t a = 1; a + 1 < n_cp && n_nz < 4; ++a)
      if (basis[a] != 0) nz[n_nz++] = a;
    for (size_t i = 0; i < n_nz; ++i) {
      const size_t a = nz[i];
      atb(a - 1, 0) += basis[a] * r.x();
      atb(a - 1, 1) += basis[a] * r.y();
      for (size_t j = 0; j < n_nz; ++j) ata(a - 1, nz[j] - 1) += basis[a] * basis[nz[j]];
    }
  }
  const Eigen::MatrixXd x = ata.ldlt().solve(atb);
  s.control.push_back(q.front());
  for (size_t c = 0; c + 2 < n_cp; ++c) s.control.emplace_back(x(c, 0), x(c, 1));
  s.control.push_back(q.back());
  for (size_t k = 0; k < m; ++k) {
    if (!((evaluate(s, t[k]) - q[k]).norm() <= tol)) return false;
    if (k + 1 < m &&
        !((evaluate(s, 0.5 * (t[k] + t[k + 1])) - 0.5 * (q[k] + q[k + 1])).norm() <= tol))
      return false;
  }
  *out = s;
  return true;
}

// A clamped cubic through q.front() and q.back() approximating q within tol (vertices and
// chord midpoints, at their chord-length parameters) with as few control points as a
// bisection finds; false when it needs more than max_control.
bool fit_cubic(const std::vector<Point2>& q, double tol, int max_control, BSpline* out) {
  const size_t m = q.size();
  std::vector<double> t(m, 0.0);
  for (size_t k = 1; k < m; ++k) t[k] = t[k - 1] + (q[k] - q[k - 1]).norm();
  const double len = t.back();
  if (!(len > 0) || m < 6) return false;
  for (double& x : t) x /= len;
  size_t hi = std::min(static_cast<size_t>(max_control), m - 3);
  if (hi < 4) return false;
  BSpline best;
  if (!try_cubic(q, t, hi, tol, &best)) return false;
  size_t lo = 3;  // fails by convention (a cubic needs 4)
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    BSpline s;
    if (try_cubic(q, t, mid, tol, &s)) {
      hi = mid;
      best = s;
    } else {
      lo = mid;
    }
  }
  for (double& k : best.knots) k *= len;
  *out = best;
  return true;
}

// Rational quadratic Bezier pieces (end weights 1, middle weight c) joined at their ends
// into one B-spline: a double knot at every joint, so each piece keeps its exact shape and
// the spline is in the form #Q frames carry (a line as its end point, an arc as its end
// point and height: docs/protocol.md).
template <typename Piece>
BSpline join_pieces(const std::vector<Piece>& pieces) {
  BSpline s;
  s.degree = 2;
  s.control.push_back(pieces.front().p0);
  s.weights.push_back(1.0);
  s.knots = {0.0, 0.0, 0.0};
  double t = 0;
  for (const Piece& a : pieces) {
    s.control.push_back(a.p1);
    s.weights.push_back(a.c);
    s.control.push_back(a.p2);
    s.weights.push_back(1.0);
    t += std::max(a.len, 1e-6);
    s.knots.push_back(t);
    s.knots.push_back(t);
  }
  s.knots.push_back(t);
  return s;
}

// Lines and arcs (vertices p) as one spline: degree 1 with no arc, else a rational
// quadratic (each line a straight Bezier, each arc in pieces of at most 90 degrees).
BSpline join_lines_and_arcs(const std::vector<Point2>& p, const std::vector<Primitive>& prims) {
  bool any_arc = false;
  for (const Primitive& pr : prims) any_arc = any_arc || pr.kind == Primitive::kArc;
  BSpline s;
  double at = 0;
  if (!any_arc) {
    s.degree = 1;
    s.control.push_back(p[prims.front().from]);
    s.knots = {0.0, 0.0};
    for (const Primitive& pr : prims) {
      at += (p[pr.to] - p[pr.from]).norm();
      s.control.push_back(p[pr.to]);
      s.knots.push_back(at);
    }
    s.knots.push_back(at);
    return s;
  }
  // Bezier pieces: each line straight (middle point), each arc in pieces of at most 90
  // degrees with the middle weight cos(half angle).
  struct Piece {
    Point2 p0, p1, p2;
    double c;    // middle weight relative to the ends
    double len;  // its knot span
  };
  std::vector<Piece> pieces;
  for (const Primitive& pr : prims) {
    if (pr.kind == Primitive::kLine) {
      pieces.push_back(Piece{p[pr.from], 0.5 * (p[pr.from] + p[pr.to]), p[pr.to], 1.0,
                             (p[pr.to] - p[pr.from]).norm()});
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(std::fabs(pr.sweep) / (kPi / 2) - 1e-9)));
    const double step = pr.sweep / n;
    const Point2 d0 = p[pr.from] - pr.centre;
    const double a0 = std::atan2(d0.y(), d0.x());
    Point2 start = p[pr.from];
    for (int k = 0; k < n; ++k) {
      const double am = a0 + step * (k + 0.5);
      const double half = std::fabs(step) / 2;
      const Point2 mid =
          pr.centre + pr.radius / std::cos(half) * Point2(std::cos(am), std::sin(am));
      const double ae = a0 + step * (k + 1);
      const Point2 end = k + 1 == n
                             ? p[pr.to]
                             : Point2(pr.centre + pr.radius * Point2(std::cos(ae), std::sin(ae)));
      pieces.push_back(Piece{start, mid, end, std::cos(half), pr.radius * std::fabs(step)});
      start = end;
    }
  }
  return join_pieces(pieces);
}

}  // namespace

std::vector<BSpline> fit_polyline(const std::vector<Point2>& in, bool closed, const FitOptions& o,
                                  FitStats* stats) {
  FitStats local;
  FitStats& st = stats ? *stats : local;
  st.input_vertices += static_cast<int>(in.size());
  // Drop repeated vertices (zero-length segments would make empty knot spans).
  std::vector<Point2> p;
  for (const Point2& q : in) {
    if (p.empty() || (q - p.back()).norm() > 1e-7) p.push_back(q);
  }
  if (closed) {
    while (p.size() > 1 && (p.back() - p.front()).norm() <= 1e-7) p.pop_back();
    if (p.size() < 2) return {};
    // Start at the longest segment so no arc is cut by the start point (unless all are arcs).
    size_t best = 0;
    double best_len = -1;
    for (size_t i = 0; i < p.size(); ++i) {
      const double l = (p[(i + 1) % p.size()] - p[i]).norm();
      if (l > best_len) best_len = l, best = i;
    }
    std::rotate(p.begin(), p.begin() + static_cast<long>(best), p.end());
    p.push_back(p.front());
  }
  if (p.size() < 2) return {};

  // Lines and arcs, greedily: the longest arc from each vertex, else one line.
  std::vector<Primitive> prims;
  const size_t n = p.size();
  for (size_t i = 0; i + 1 < n;) {
    Primitive arc;
    size_t j = i + static_cast<size_t>(o.min_arc_segments);
    if (j < n && fits_arc(p, i, j, o.tolerance_mm, &arc)) {
      Primitive longer;
      while (j + 1 < n && fits_arc(p, i, j + 1, o.tolerance_mm, &longer)) arc = longer, ++j;
      arc.sweep = arc_sweep(p, arc.from, arc.to, arc.centre);
      prims.push_back(arc);
      i = j;
      continue;
    }
    Primitive line;
    line.from = i;
    line.to = i + 1;
    prims.push_back(line);
    i = i + 1;
  }

  // Runs of short segments (whatever the arcs and lines found in them): a cubic when it
  // needs clearly fewer control points than the quadratic pieces (two per line and per
  // quarter of an arc).
  auto quad_cost = [](const Primitive& pr) {
    if (pr.kind == Primitive::kLine) return 2;
    return 2 * std::max(1, static_cast<int>(std::ceil(std::fabs(pr.sweep) / (kPi / 2) - 1e-9)));
  };
  auto short_prim = [&](const Primitive& pr) {
    for (size_t v = pr.from; v < pr.to; ++v)
      if ((p[v + 1] - p[v]).norm() >= o.short_segment_mm) return false;
    return true;
  };
  std::vector<Primitive> merged;
  for (size_t k = 0; k < prims.size();) {
    size_t e = k;
    int cost = 0, segments = 0;
    while (e < prims.size() && short_prim(prims[e])) {
      cost += quad_cost(prims[e]);
      segments += static_cast<int>(prims[e].to - prims[e].from);
      ++e;
    }
    if (segments >= o.min_cubic_segments) {
      std::vector<Point2> q(p.begin() + static_cast<long>(prims[k].from),
                            p.begin() + static_cast<long>(prims[e - 1].to) + 1);
      Primitive c;
      // A spline of its own costs a header and knots: worth it only when clearly smaller.
      const int max_control = cost - 6;
      if (max_control >= 4 && fit_cubic(q, o.tolerance_mm, max_control, &c.cubic)) {
        c.kind = Primitive::kCubic;
        c.from = prims[k].from;
        c.to = prims[e - 1].to;
        merged.push_back(c);
        ++st.cubics;
        k = e;
        continue;
      }
    }
    if (e == k) e = k + 1;
    for (; k < e; ++k) {
      if (prims[k].kind == Primitive::kLine) ++st.lines;
      if (prims[k].kind == Primitive::kArc) ++st.arcs;
      merged.push_back(prims[k]);
    }
  }

  std::vector<BSpline> out;
  std::vector<Primitive> run;
  for (const Primitive& pr : merged) {
    if (pr.kind == Primitive::kCubic) {
      if (!run.empty()) out.push_back(join_lines_and_arcs(p, run));
      run.clear();
      out.push_back(pr.cubic);
    } else {
      run.push_back(pr);
    }
  }
  if (!run.empty()) out.push_back(join_lines_and_arcs(p, run));
  return out;
}

namespace {

double point_segment_distance(const Point2& x, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double l2 = ab.squaredNorm();
  double t = l2 > 0 ? (x - a).dot(ab) / l2 : 0.0;
  t = std::max(0.0, std::min(1.0, t));
  return (a + t * ab - x).norm();
}

}  // namespace

double max_deviation_mm(const std::vector<Point2>& pts, bool closed,
                        const std::vector<BSpline>& curves) {
  std::vector<Point2> dense;
  for (const BSpline& c : curves) {
    const std::vector<Point2> s = sample(c, 0.0001);
    dense.insert(dense.end(), s.begin(), s.end());
  }
  (void)closed;
  double worst = 0;
  for (const Point2& x : pts) {
    double best = 1e300;
    for (size_t k = 0; k + 1 < dense.size(); ++k)
      best = std::min(best, point_segment_distance(x, dense[k], dense[k + 1]));
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace host::pcb
