// The outline of a disc swept along an open path (see disc_outline.h).
#include "host/lib/pcb/disc_outline.h"

#include <algorithm>  // std::min, std::reverse
#include <cmath>      // std::acos, std::atan2, std::ceil, std::cos, std::fabs, std::llround
#include <vector>     // std::vector

#include "host/lib/drawing/bspline.h"  // Point2

namespace host::pcb {

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;

// The left normal of a unit direction.
Point2 left_of(const Point2& d) {
  return Point2(-d.y(), d.x());
}

class OutlineWriter {
 public:
  OutlineWriter(double radius_nm, double step_rad, Path* out)
      : r_(radius_nm), step_(step_rad), out_(out) {}

  void point(const Point2& p) {
    const IntPoint q(static_cast<cInt>(std::llround(p.x())),
                     static_cast<cInt>(std::llround(p.y())));
    if (out_->empty() || out_->back().X != q.X || out_->back().Y != q.Y) out_->push_back(q);
  }

  // The circle about c from angle a0 clockwise by sweep (>= 0), the ends left out.
  void clockwise_arc(const Point2& c, double a0, double sweep) {
    const int n = static_cast<int>(std::ceil(sweep / step_));
    for (int k = 1; k < n; ++k) {
      const double a = a0 - sweep * k / n;
      point(c + r_ * Point2(std::cos(a), std::sin(a)));
    }
  }

  // The left side of p (no repeated points, at least two) from its start to its end.
  void left_side(const std::vector<Point2>& p) {
    const size_t n = p.size();
    Point2 d_prev = (p[1] - p[0]).normalized();
    point(p[0] + r_ * left_of(d_prev));
    for (size_t i = 1; i + 1 < n; ++i) {
      const Point2 d = (p[i + 1] - p[i]).normalized();
      join(p[i], d_prev, d, (p[i] - p[i - 1]).norm(), (p[i + 1] - p[i]).norm());
      d_prev = d;
    }
    point(p[n - 1] + r_ * left_of(d_prev));
  }

  // The end cap at p's last point: from the left side's end around to the right side's start.
  void end_cap(const std::vector<Point2>& p) {
    const Point2 n = left_of((p.back() - p[p.size() - 2]).normalized());
    clockwise_arc(p.back(), std::atan2(n.y(), n.x()), EIGEN_PI);
  }

 private:
  // The left side at vertex v between the unit directions a (in) and b (out).
  void join(const Point2& v, const Point2& a, const Point2& b, double len_a, double len_b) {
    const Point2 na = left_of(a), nb = left_of(b);
    const double cross = a.x() * b.y() - a.y() * b.x();
    const double cos_turn = a.dot(b);
    if (cross > 0) {
      // A left turn: the inside. The offset edges cross r tan(turn / 2) back from their ends;
      // where that is on both edges it is the boundary's corner.
      const double back = 1 + cos_turn > 1e-12 ? r_ * cross / (1 + cos_turn) : len_a + len_b;
      if (back <= len_a && back <= len_b) {
        point(v + (na + nb) * (r_ / (1 + cos_turn)));
      } else {
        point(v + r_ * na);
        point(v);
        point(v + r_ * nb);
      }
      return;
    }
    // A right turn, straight on or back: the outside, round about v by the turn (0 .. pi;
    // from the sine and cosine, so a straight run's rounding never reads as a full circle,
    // and straight back rounds the tip).
    point(v + r_ * na);
    clockwise_arc(v, std::atan2(na.y(), na.x()), std::atan2(std::fabs(cross), cos_turn));
    point(v + r_ * nb);
  }

  double r_, step_;
  Path* out_;
};

}  // namespace

Path disc_sweep_outline(const Path& path, double radius_nm, double arc_tolerance_nm) {
  Path out;
  if (path.empty() || !(radius_nm > 0)) return out;
  // Chords within the tolerance, as ClipperOffset makes them (at most a quarter of r).
  const double tol = std::min(arc_tolerance_nm, radius_nm / 4);
  const double step = 2 * std::acos(1 - tol / radius_nm);
  std::vector<Point2> p;
  for (const IntPoint& q : path) {
    const Point2 v(static_cast<double>(q.X), static_cast<double>(q.Y));
    if (p.empty() || p.back() != v) p.push_back(v);
  }
  OutlineWriter w(radius_nm, step, &out);
  if (p.size() == 1) {  // a disc
    w.point(p[0] + Point2(radius_nm, 0));
    w.clockwise_arc(p[0], 0, 2 * EIGEN_PI);
    return out;
  }
  w.left_side(p);
  w.end_cap(p);
  std::reverse(p.begin(), p.end());
  w.left_side(p);
  w.end_cap(p);
  return out;
}

}  // namespace host::pcb
