// Tool-centre runs near copper, found with a grid of the copper's edges (see near_copper.h).
#include "host/lib/pcb/near_copper.h"

#include <algorithm>  // std::min, std::max
#include <cmath>      // std::floor, std::sqrt
#include <cstdint>    // uint32_t, UINT32_MAX
#include <vector>     // std::vector

#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

struct Seg {
  double ax, ay, bx, by;
};

double dist2_point_seg(double px, double py, const Seg& s) {
  const double dx = s.bx - s.ax, dy = s.by - s.ay;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - s.ax) * dx + (py - s.ay) * dy) / len2 : 0;
  t = std::max(0.0, std::min(1.0, t));
  const double ex = s.ax + t * dx - px, ey = s.ay + t * dy - py;
  return ex * ex + ey * ey;
}

double cross(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// Squared distance between two segments (0 when they cross).
double dist2_seg_seg(const Seg& a, const Seg& b) {
  const double d1 = cross(a.ax, a.ay, a.bx, a.by, b.ax, b.ay);
  const double d2 = cross(a.ax, a.ay, a.bx, a.by, b.bx, b.by);
  const double d3 = cross(b.ax, b.ay, b.bx, b.by, a.ax, a.ay);
  const double d4 = cross(b.ax, b.ay, b.bx, b.by, a.bx, a.by);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 0;
  return std::min(std::min(dist2_point_seg(a.ax, a.ay, b), dist2_point_seg(a.bx, a.by, b)),
                  std::min(dist2_point_seg(b.ax, b.ay, a), dist2_point_seg(b.bx, b.by, a)));
}

// The copper's edges bucketed in square cells (compressed rows: cell k holds
// edge_of[first[k] .. first[k + 1])).
class EdgeGrid {
 public:
  EdgeGrid(const Paths& copper, double cell_nm) : copper_(copper), cell_(cell_nm) {
    const BoxNm b = box_of(copper);
    if (b.empty()) return;
    x0_ = static_cast<double>(b.min_x);
    y0_ = static_cast<double>(b.min_y);
    // At most about a million cells, whatever the reach.
    const double w = static_cast<double>(b.max_x) - x0_, h = static_cast<double>(b.max_y) - y0_;
    cell_ = std::max(cell_, std::sqrt(w * h / 1e6));
    nx_ = static_cast<int>((static_cast<double>(b.max_x) - x0_) / cell_) + 1;
    ny_ = static_cast<int>((static_cast<double>(b.max_y) - y0_) / cell_) + 1;
    for (uint32_t k = 0; k < copper.size(); ++k)
      for (uint32_t i = 0; i < copper[k].size(); ++i) edges_.push_back(edge(k, i));
    first_.assign(static_cast<size_t>(nx_) * ny_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        for (size_t k = 1; k < first_.size(); ++k) first_[k] += first_[k - 1];
        edge_of_.resize(first_.back());
        fill_ = std::vector<size_t>(first_.begin(), first_.end() - 1);
      }
      for (size_t e = 0; e < edges_.size(); ++e) {
        const Seg& s = edges_[e];
        int cx0, cy0, cx1, cy1;
        cells(std::min(s.ax, s.bx), std::min(s.ay, s.by), std::max(s.ax, s.bx),
              std::max(s.ay, s.by), &cx0, &cy0, &cx1, &cy1);
        for (int y = cy0; y <= cy1; ++y)
          for (int x = cx0; x <= cx1; ++x) {
            const size_t k = static_cast<size_t>(y) * nx_ + x;
            if (pass == 0)
              ++first_[k + 1];
            else
              edge_of_[fill_[k]++] = static_cast<uint32_t>(e);
          }
      }
    }
  }

  // Whether some edge comes closer than reach to the segment. *last is the edge found
  // near the previous segment, tried first (a tool path runs along one copper edge for
  // many segments).
  bool near(const Seg& s, double reach, uint32_t* last) const {
    if (nx_ == 0) return false;
    const double r2 = reach * reach;
    if (*last < edges_.size() && dist2_seg_seg(s, edges_[*last]) < r2) return true;
    const double x0 = std::min(s.ax, s.bx) - reach, y0 = std::min(s.ay, s.by) - reach;
    const double x1 = std::max(s.ax, s.bx) + reach, y1 = std::max(s.ay, s.by) + reach;
    int cx0, cy0, cx1, cy1;
    cells(x0, y0, x1, y1, &cx0, &cy0, &cx1, &cy1);
    for (int y = cy0; y <= cy1; ++y)
      for (int x = cx0; x <= cx1; ++x) {
        const size_t k = static_cast<size_t>(y) * nx_ + x;
        for (size_t i = first_[k]; i < first_[k + 1]; ++i) {
          // Most edges of a clean job are beyond reach: their boxes tell it cheaply.
          const Seg& e = edges_[edge_of_[i]];
          if (std::max(e.ax, e.bx) < x0 || std::min(e.ax, e.bx) > x1 || std::max(e.ay, e.by) < y0 ||
              std::min(e.ay, e.by) > y1)
            continue;
          // Both ends beyond reach of the edge's line, on one side of it: so is the whole
          // segment (a long edge lies in many cells, and a tool path runs along it).
          const double ex = e.bx - e.ax, ey = e.by - e.ay;
          const double ca = ex * (s.ay - e.ay) - ey * (s.ax - e.ax);
          const double cb = ex * (s.by - e.ay) - ey * (s.bx - e.ax);
          const double beyond = r2 * (ex * ex + ey * ey);
          if ((ca > 0) == (cb > 0) && ca * ca > beyond && cb * cb > beyond) continue;
          if (dist2_seg_seg(s, e) < r2) {
            *last = edge_of_[i];
            return true;
          }
        }
      }
    return false;
  }

 private:
  // The edge from vertex i of path k to the next.
  Seg edge(uint32_t k, uint32_t i) const {
    const Path& p = copper_[k];
    const IntPoint& u = p[i];
    const IntPoint& v = p[(i + 1) % p.size()];
    return {static_cast<double>(u.X), static_cast<double>(u.Y), static_cast<double>(v.X),
            static_cast<double>(v.Y)};
  }

  // The cells a box covers, clamped to the grid (a box beyond it covers the border cells,
  // which is only more work).
  void cells(double x0, double y0, double x1, double y1, int* cx0, int* cy0, int* cx1,
             int* cy1) const {
    auto clamp = [](double v, int n) {
      return static_cast<int>(std::max(0.0, std::min(static_cast<double>(n - 1), v)));
    };
    *cx0 = clamp(std::floor((x0 - x0_) / cell_), nx_);
    *cx1 = clamp(std::floor((x1 - x0_) / cell_), nx_);
    *cy0 = clamp(std::floor((y0 - y0_) / cell_), ny_);
    *cy1 = clamp(std::floor((y1 - y0_) / cell_), ny_);
  }

  const Paths& copper_;
  double cell_;
  double x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<Seg> edges_;
  std::vector<size_t> first_, fill_;
  std::vector<uint32_t> edge_of_;
};

// Inside the copper by even-odd over all its paths.
bool inside_copper(const IntPoint& p, const Paths& copper, const std::vector<BoxNm>& boxes) {
  bool inside = false;
  for (size_t i = 0; i < copper.size(); ++i)
    if (boxes[i].contains(p) && ClipperLib::PointInPolygon(p, copper[i]) != 0) inside = !inside;
  return inside;
}

}  // namespace

Paths runs_near_copper(const Paths& centres, const Paths& copper, double reach_nm) {
  Paths runs;
  if (copper.empty()) return runs;
  // Rounding of the doubles, and of the integer paths either side: a micrometre more.
  const double reach = reach_nm + 1000.0;
  const EdgeGrid grid(copper, std::max(2 * reach, 50e3));
  std::vector<BoxNm> boxes(copper.size());
  for (size_t i = 0; i < copper.size(); ++i) boxes[i].add(copper[i]);
  for (const Path& p : centres) {
    if (p.empty()) continue;
    const size_t n = p.size() == 1 ? 1 : p.size() - 1;  // segments (a point: one)
    // A run of segments far from every edge lies wholly inside or wholly outside copper
    // (crossing an edge comes within reach of it): one vertex tells which.
    std::vector<char> keep(n, 0);
    size_t far_from = n;  // first segment of the current far run
    uint32_t last_near = UINT32_MAX;
    for (size_t i = 0; i <= n; ++i) {
      bool is_near = true;
      if (i < n) {
        const IntPoint& a = p[i];
        const IntPoint& b = p[p.size() == 1 ? 0 : i + 1];
        const Seg s{static_cast<double>(a.X), static_cast<double>(a.Y), static_cast<double>(b.X),
                    static_cast<double>(b.Y)};
        is_near = grid.near(s, reach, &last_near);
        keep[i] = is_near;
        if (!is_near && far_from == n) far_from = i;
      }
      if (is_near && far_from != n) {
        if (inside_copper(p[far_from], copper, boxes))
          for (size_t k = far_from; k < i; ++k) keep[k] = 1;
        far_from = n;
      }
    }
    for (size_t i = 0; i < n;) {
      if (!keep[i]) {
        ++i;
        continue;
      }
      Path run{p[i]};
      while (i < n && keep[i]) {
        run.push_back(p[p.size() == 1 ? 0 : i + 1]);
        ++i;
      }
      runs.push_back(run);
    }
  }
  return runs;
}

}  // namespace host::pcb
