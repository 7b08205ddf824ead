#include "host/lib/pcb/gerber_shapes.h"

#include <algorithm>  // std::sort
#include <cmath>      // std::acos, std::ceil, std::cos, std::sin, std::llround

namespace host::pcb {

namespace {

const double kPi = 3.14159265358979323846;

// Segments for a sweep so that the chord error stays within tol.
int arc_segments(double r_nm, double sweep, double tol_nm) {
  const double full = circle_segments(r_nm, tol_nm);
  const int n = static_cast<int>(std::ceil(full * std::fabs(sweep) / (2 * kPi)));
  return n < 1 ? 1 : n;
}

}  // namespace

int circle_segments(double r_nm, double tol_nm) {
  if (!(r_nm > tol_nm) || !(tol_nm > 0)) return 8;
  // Chord error of a segment spanning angle t: r (1 - cos(t/2)).
  const double step = 2 * std::acos(1 - tol_nm / r_nm);
  const double n = std::ceil(2 * kPi / step);
  if (n < 8) return 8;
  return n > 100000 ? 100000 : static_cast<int>(n);
}

IntPoint to_int(VecNm p) {
  return IntPoint(static_cast<cInt>(std::llround(p.x)), static_cast<cInt>(std::llround(p.y)));
}

Path circle_path(VecNm c, double diameter_nm, double tol_nm) {
  const double r = diameter_nm / 2;
  const int n = circle_segments(r, tol_nm);
  Path p;
  p.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    p.push_back(to_int({c.x + r * std::cos(a), c.y + r * std::sin(a)}));
  }
  return p;
}

Path rect_path(VecNm c, double w, double h) {
  return {to_int({c.x - w / 2, c.y - h / 2}), to_int({c.x + w / 2, c.y - h / 2}),
          to_int({c.x + w / 2, c.y + h / 2}), to_int({c.x - w / 2, c.y + h / 2})};
}

Path obround_path(VecNm c, double w, double h, double tol_nm) {
  if (w == h) return circle_path(c, w, tol_nm);
  const double r = std::min(w, h) / 2;
  const double half = (std::max(w, h) - std::min(w, h)) / 2;
  const VecNm a = w > h ? VecNm{c.x - half, c.y} : VecNm{c.x, c.y - half};
  const VecNm b = w > h ? VecNm{c.x + half, c.y} : VecNm{c.x, c.y + half};
  return capsule_path(a, b, 2 * r, tol_nm);
}

Path regular_polygon_path(VecNm c, double diameter_nm, int vertices, double rotation_deg) {
  Path p;
  const double r = diameter_nm / 2;
  for (int i = 0; i < vertices; ++i) {
    const double a = rotation_deg * kPi / 180 + 2 * kPi * i / vertices;
    p.push_back(to_int({c.x + r * std::cos(a), c.y + r * std::sin(a)}));
  }
  return p;
}

Path capsule_path(VecNm a, VecNm b, double diameter_nm, double tol_nm) {
  const double r = diameter_nm / 2;
  const double dir = std::atan2(b.y - a.y, b.x - a.x);
  const int half = std::max(2, (circle_segments(r, tol_nm) + 1) / 2);
  Path p;
  p.reserve(static_cast<size_t>(2 * half + 2));
  // Around b from dir-90 to dir+90, then around a from dir+90 to dir+270.
  for (int i = 0; i <= half; ++i) {
    const double t = dir - kPi / 2 + kPi * i / half;
    p.push_back(to_int({b.x + r * std::cos(t), b.y + r * std::sin(t)}));
  }
  for (int i = 0; i <= half; ++i) {
    const double t = dir + kPi / 2 + kPi * i / half;
    p.push_back(to_int({a.x + r * std::cos(t), a.y + r * std::sin(t)}));
  }
  return p;
}

Path convex_hull(Path pts) {
  std::sort(pts.begin(), pts.end(), [](const IntPoint& l, const IntPoint& r) {
    return l.X < r.X || (l.X == r.X && l.Y < r.Y);
  });
  if (pts.size() < 3) return pts;
  auto cross = [](const IntPoint& o, const IntPoint& a, const IntPoint& b) {
    return static_cast<double>(a.X - o.X) * static_cast<double>(b.Y - o.Y) -
           static_cast<double>(a.Y - o.Y) * static_cast<double>(b.X - o.X);
  };
  Path hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {  // upper hull
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

void append_arc(Path& out, VecNm c, double r0, double r1, double a0, double sweep, double tol_nm) {
  const int n = arc_segments(std::max(r0, r1), sweep, tol_nm);
  for (int i = 1; i <= n; ++i) {
    const double f = static_cast<double>(i) / n;
    const double a = a0 + sweep * f;
    const double r = r0 + (r1 - r0) * f;
    out.push_back(to_int({c.x + r * std::cos(a), c.y + r * std::sin(a)}));
  }
}

void rotate_path(Path& path, double degrees) {
  if (degrees == 0) return;
  const double a = degrees * kPi / 180, c = std::cos(a), s = std::sin(a);
  for (IntPoint& p : path) {
    const double x = static_cast<double>(p.X), y = static_cast<double>(p.Y);
    p = to_int({x * c - y * s, x * s + y * c});
  }
}

void translate_paths(Paths& paths, cInt dx, cInt dy) {
  for (Path& p : paths) {
    for (IntPoint& q : p) {
      q.X += dx;
      q.Y += dy;
    }
  }
}

void make_positive(Path& path) {
  if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
}

void split_by_box(const Paths& all, const BoxNm& box, Paths& touched, Paths& kept) {
  for (const Path& p : all) {
    BoxNm b;
    b.add(p);
    (b.overlaps(box) ? touched : kept).push_back(p);
  }
}

Paths union_objects(const Paths& paths, const std::vector<size_t>& starts, const Paths& base) {
  std::vector<Paths> objects;
  objects.reserve(starts.size());
  for (size_t k = 0; k < starts.size(); ++k) {
    const size_t end = k + 1 < starts.size() ? starts[k + 1] : paths.size();
    if (starts[k] < end) {
      objects.emplace_back(paths.begin() + static_cast<long>(starts[k]),
                           paths.begin() + static_cast<long>(end));
    }
  }
  Paths all = united_by_strips(objects, union_of);
  if (base.empty()) return all;
  all.insert(all.end(), base.begin(), base.end());
  return union_of(all);
}

}  // namespace host::pcb
