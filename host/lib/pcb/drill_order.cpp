// Drill grouping and ordering (see drill_order.h).
#include "host/lib/pcb/drill_order.h"

#include <algorithm>  // std::reverse, std::sort
#include <cmath>      // std::llround
#include <map>        // std::map

namespace host::pcb {

double travel_mm(const Point2& start, const std::vector<Point2>& pts) {
  double t = 0;
  Point2 at = start;
  for (const Point2& p : pts) {
    t += (p - at).norm();
    at = p;
  }
  return t;
}

std::vector<size_t> short_tour(const Point2& start, const std::vector<Point2>& pts) {
  const size_t n = pts.size();
  std::vector<size_t> order;
  std::vector<bool> used(n, false);
  Point2 at = start;
  for (size_t k = 0; k < n; ++k) {
    size_t best = 0;
    double best_d = 1e300;
    for (size_t i = 0; i < n; ++i) {
      if (used[i]) continue;
      const double d = (pts[i] - at).squaredNorm();
      if (d < best_d) best_d = d, best = i;
    }
    used[best] = true;
    order.push_back(best);
    at = pts[best];
  }
  // 2-opt on the open path with a fixed start: reversing order[i..j] replaces the edges
  // (prev(i), i) and (j, next(j)); the last hole has no successor.
  auto pos = [&](long k) { return k < 0 ? start : pts[order[static_cast<size_t>(k)]]; };
  bool improved = true;
  for (int round = 0; improved && round < 100; ++round) {
    improved = false;
    for (long i = 0; i + 1 < static_cast<long>(n); ++i) {
      for (long j = i + 1; j < static_cast<long>(n); ++j) {
        const Point2 a = pos(i - 1), b = pos(i), c = pos(j);
        double before = (b - a).norm(), after = (c - a).norm();
        if (j + 1 < static_cast<long>(n)) {
          const Point2 d = pos(j + 1);
          before += (d - c).norm();
          after += (d - b).norm();
        }
        if (after < before - 1e-9) {
          std::reverse(order.begin() + i, order.begin() + j + 1);
          improved = true;
        }
      }
    }
  }
  return order;
}

DrillPlan order_holes(const std::vector<Point2>& at, const std::vector<double>& diameter,
                      const std::vector<int>& tool, const Point2& start) {
  DrillPlan plan;
  plan.travel_file_order_mm = travel_mm(start, at);
  std::map<long long, std::vector<size_t>> by_size;  // diameter in um -> holes
  for (size_t i = 0; i < at.size(); ++i) by_size[std::llround(diameter[i] * 1000.0)].push_back(i);
  Point2 from = start;
  for (const auto& entry : by_size) {
    DrillGroup g;
    g.diameter_mm = diameter[entry.second.front()];
    g.tool = tool[entry.second.front()];
    std::vector<Point2> pts;
    for (size_t i : entry.second) pts.push_back(at[i]);
    for (size_t k : short_tour(from, pts)) {
      g.holes_mm.push_back(pts[k]);
      g.file_index.push_back(entry.second[k]);
    }
    plan.travel_ordered_mm += travel_mm(from, g.holes_mm);
    from = g.holes_mm.back();
    plan.groups.push_back(g);
  }
  return plan;
}

}  // namespace host::pcb
