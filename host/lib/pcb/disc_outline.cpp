// The outline of a disc swept along an open path (see disc_outline.h).
#include "host/lib/pcb/disc_outline.h"

#include <algorithm>  // std::min, std::reverse
#include <cmath>  // std::acos, std::atan2, std::ceil, std::cos, std::fabs, std::hypot, std::llround
#include <vector>  // std::vector

namespace host::pcb {

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;

const double kPi = 3.14159265358979323846;

struct Vec {
  double x, y;
};

class OutlineWriter {
 public:
  OutlineWriter(double radius_nm, double step_rad, Path* out)
      : r_(radius_nm), step_(step_rad), out_(out) {}

  void point(double x, double y) {
    const IntPoint q(static_cast<cInt>(std::llround(x)), static_cast<cInt>(std::llround(y)));
    if (out_->empty() || out_->back().X != q.X || out_->back().Y != q.Y) out_->push_back(q);
  }

  // The circle about c from angle a0 clockwise by sweep (>= 0), the ends left out.
  void clockwise_arc(const Vec& c, double a0, double sweep) {
    const int n = static_cast<int>(std::ceil(sweep / step_));
    for (int k = 1; k < n; ++k) {
      const double a = a0 - sweep * k / n;
      point(c.x + r_ * std::cos(a), c.y + r_ * std::sin(a));
    }
  }

  // The left side of p (no repeated points, at least two) from its start to its end.
  void left_side(const std::vector<Vec>& p) {
    const size_t n = p.size();
    Vec d_prev = unit(p[0], p[1]);
    point(p[0].x - d_prev.y * r_, p[0].y + d_prev.x * r_);
    for (size_t i = 1; i + 1 < n; ++i) {
      const Vec d = unit(p[i], p[i + 1]);
      join(p[i], d_prev, d, length(p[i - 1], p[i]), length(p[i], p[i + 1]));
      d_prev = d;
    }
    point(p[n - 1].x - d_prev.y * r_, p[n - 1].y + d_prev.x * r_);
  }

  // The end cap at p's last point: from the left side's end around to the right side's start.
  void end_cap(const std::vector<Vec>& p) {
    const Vec d = unit(p[p.size() - 2], p.back());
    clockwise_arc(p.back(), std::atan2(d.x, -d.y), kPi);
  }

 private:
  static double length(const Vec& a, const Vec& b) { return std::hypot(b.x - a.x, b.y - a.y); }
  static Vec unit(const Vec& a, const Vec& b) {
    const double l = length(a, b);
    return {(b.x - a.x) / l, (b.y - a.y) / l};
  }

  // The left side at vertex v between the directions a (in) and b (out).
  void join(const Vec& v, const Vec& a, const Vec& b, double len_a, double len_b) {
    const Vec na{-a.y, a.x}, nb{-b.y, b.x};  // left normals
    const double cross = a.x * b.y - a.y * b.x;
    const double cos_turn = a.x * b.x + a.y * b.y;
    if (cross > 0) {
      // A left turn: the inside. The offset edges cross r tan(turn / 2) back from their ends;
      // where that is on both edges it is the boundary's corner.
      const double back = 1 + cos_turn > 1e-12 ? r_ * cross / (1 + cos_turn) : len_a + len_b;
      if (back <= len_a && back <= len_b) {
        const double k = r_ / (1 + cos_turn);
        point(v.x + (na.x + nb.x) * k, v.y + (na.y + nb.y) * k);
      } else {
        point(v.x + na.x * r_, v.y + na.y * r_);
        point(v.x, v.y);
        point(v.x + nb.x * r_, v.y + nb.y * r_);
      }
      return;
    }
    // A right turn, straight on or back: the outside, round about v by the turn (0 .. pi;
    // from the sine and cosine, so a straight run's rounding never reads as a full circle,
    // and straight back rounds the tip).
    point(v.x + na.x * r_, v.y + na.y * r_);
    clockwise_arc(v, std::atan2(na.y, na.x), std::atan2(std::fabs(cross), cos_turn));
    point(v.x + nb.x * r_, v.y + nb.y * r_);
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
  std::vector<Vec> p;
  for (const IntPoint& q : path) {
    const Vec v{static_cast<double>(q.X), static_cast<double>(q.Y)};
    if (p.empty() || p.back().x != v.x || p.back().y != v.y) p.push_back(v);
  }
  OutlineWriter w(radius_nm, step, &out);
  if (p.size() == 1) {  // a disc
    w.point(p[0].x + radius_nm, p[0].y);
    w.clockwise_arc(p[0], 0, 2 * kPi);
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
