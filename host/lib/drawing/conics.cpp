// Lines, arcs, ellipses and bulge polylines as exact (rational) B-splines.
#include "host/lib/drawing/conics.h"

#include <algorithm>  // std::max
#include <cmath>      // std::cos, std::ceil

namespace host {

namespace {

// A rational quadratic Bezier piece: ends p0, p2; middle p1 with weight w1.
struct QuadPiece {
  Point2 p0, p1, p2;
  double w1;
};

const double kPi = 3.14159265358979323846;

// Pieces of a circular arc, each at most 90 degrees; ends exactly at the given points when
// supplied (so a polyline stays connected bit for bit).
void arc_pieces(const Point2& c, double r, double a0, double sweep, std::vector<QuadPiece>& out) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::fabs(sweep) / (kPi / 2) - 1e-9)));
  const double step = sweep / n;
  const double w = std::cos(step / 2);
  for (int i = 0; i < n; ++i) {
    const double s = a0 + step * i;
    const double e = s + step;
    const double m = s + step / 2;
    QuadPiece q;
    q.p0 = c + r * Point2(std::cos(s), std::sin(s));
    q.p2 = c + r * Point2(std::cos(e), std::sin(e));
    q.p1 = c + (r / w) * Point2(std::cos(m), std::sin(m));
    q.w1 = w;
    out.push_back(q);
  }
}

// Joins quadratic pieces (each starting where the previous ended) into one B-spline with
// double interior knots.
BSpline join_pieces(const std::vector<QuadPiece>& pieces) {
  BSpline s;
  s.degree = 2;
  bool rational = false;
  for (const QuadPiece& q : pieces) rational = rational || q.w1 != 1.0;
  s.control.push_back(pieces.front().p0);
  s.weights.push_back(1.0);
  s.knots = {0, 0, 0};
  for (size_t i = 0; i < pieces.size(); ++i) {
    s.control.push_back(pieces[i].p1);
    s.weights.push_back(pieces[i].w1);
    s.control.push_back(pieces[i].p2);
    s.weights.push_back(1.0);
    const double k = static_cast<double>(i + 1);
    s.knots.push_back(k);
    s.knots.push_back(k);
  }
  s.knots.push_back(static_cast<double>(pieces.size()));
  if (!rational) s.weights.clear();
  return s;
}

}  // namespace

BSpline line_spline(const Point2& a, const Point2& b) {
  BSpline s;
  s.degree = 1;
  s.control = {a, b};
  s.knots = {0, 0, 1, 1};
  return s;
}

BSpline arc_spline(const Point2& centre, double radius, double start_rad, double sweep_rad) {
  std::vector<QuadPiece> pieces;
  arc_pieces(centre, radius, start_rad, sweep_rad, pieces);
  return join_pieces(pieces);
}

BSpline ellipse_spline(const Point2& centre, const Point2& major, const Point2& minor, double t0,
                       double sweep) {
  Eigen::Matrix2d a;
  a.col(0) = major;
  a.col(1) = minor;
  return transformed(arc_spline(Point2(0, 0), 1.0, t0, sweep), a, centre);
}

BSpline polyline_spline(const std::vector<BulgeVertex>& vertices, bool closed) {
  std::vector<QuadPiece> pieces;
  std::vector<Point2> corners;  // for the all-straight case
  bool any_bulge = false;
  const size_t n = vertices.size();
  const size_t segments = closed ? n : (n == 0 ? 0 : n - 1);
  for (size_t i = 0; i < segments; ++i) {
    const Point2 a = vertices[i].p;
    const Point2 b = vertices[(i + 1) % n].p;
    const double chord = (b - a).norm();
    if (!(chord > 1e-9)) continue;  // zero-length segment: nothing to draw
    if (corners.empty()) corners.push_back(a);
    corners.push_back(b);
    const double bulge = vertices[i].bulge;
    if (bulge == 0.0) {
      QuadPiece q = {a, 0.5 * (a + b), b, 1.0};
      pieces.push_back(q);
      continue;
    }
    any_bulge = true;
    // Sweep 4 atan(bulge); the centre lies on the chord's left normal for a CCW arc under
    // 180 degrees, at (chord / 2) / tan(sweep / 2) from the chord's midpoint.
    const double sweep = 4.0 * std::atan(bulge);
    const Point2 dir = (b - a) / chord;
    const Point2 left(-dir.y(), dir.x());
    const Point2 centre = 0.5 * (a + b) + left * (0.5 * chord / std::tan(sweep / 2));
    const double radius = (a - centre).norm();
    const Point2 ra = a - centre;
    std::vector<QuadPiece> arc;
    arc_pieces(centre, radius, std::atan2(ra.y(), ra.x()), sweep, arc);
    arc.front().p0 = a;  // exact joints
    arc.back().p2 = b;
    pieces.insert(pieces.end(), arc.begin(), arc.end());
  }
  if (pieces.empty()) return BSpline();
  if (!any_bulge) {
    BSpline s;
    s.degree = 1;
    s.control = corners;
    s.knots.push_back(0);
    for (size_t i = 0; i < corners.size(); ++i) s.knots.push_back(static_cast<double>(i));
    s.knots.push_back(static_cast<double>(corners.size() - 1));
    return s;
  }
  return join_pieces(pieces);
}

}  // namespace host
