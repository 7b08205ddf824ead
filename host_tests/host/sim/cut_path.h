// The cut path of a simulated run (pen-down trace segments) and how far two cut paths are
// apart: for tests that compare an interrupted and resumed job with an uninterrupted one.
#ifndef HOST_TESTS_HOST_SIM_CUT_PATH_H
#define HOST_TESTS_HOST_SIM_CUT_PATH_H

#include <algorithm>  // std::min, std::max
#include <cmath>      // std::hypot, std::floor
#include <map>        // std::map
#include <utility>    // std::pair
#include <vector>     // std::vector

#include "host/lib/sim/sim_job.h"  // pen_threshold_mm, ToolSample

namespace host::test {

// Which trace samples cut: below the plan's pen threshold after the tool was first lifted (at
// power-on the tool stands at Z 0, which is below the threshold but not cutting).
inline std::vector<bool> pen_down_samples(const std::vector<sim::ToolSample>& trace,
                                          const JobPlan& plan) {
  const double pen = sim::pen_threshold_mm(plan);
  std::vector<bool> down(trace.size(), false);
  bool lifted = false;
  for (size_t i = 0; i < trace.size(); ++i) {
    if (trace[i].z_mm >= pen) lifted = true;
    down[i] = lifted && trace[i].z_mm < pen;
  }
  return down;
}

// The cut path: pen-down trace segments (X/Y in mm) and their total length.
struct CutPath {
  struct Seg {
    double x0, y0, x1, y1;
  };
  std::vector<Seg> segs;
  double length_mm = 0;
};

inline CutPath cut_path(const std::vector<sim::ToolSample>& trace, const JobPlan& plan) {
  const std::vector<bool> down = pen_down_samples(trace, plan);
  CutPath p;
  for (size_t i = 1; i < trace.size(); ++i) {
    if (!down[i] || !down[i - 1]) continue;
    const CutPath::Seg s{trace[i - 1].x_mm, trace[i - 1].y_mm, trace[i].x_mm, trace[i].y_mm};
    const double len = std::hypot(s.x1 - s.x0, s.y1 - s.y0);
    if (len == 0) continue;
    p.segs.push_back(s);
    p.length_mm += len;
  }
  return p;
}

inline double point_segment_mm(double x, double y, const CutPath::Seg& s) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((x - s.x0) * dx + (y - s.y0) * dy) / l2 : 0;
  t = std::min(1.0, std::max(0.0, t));
  return std::hypot(x - (s.x0 + t * dx), y - (s.y0 + t * dy));
}

// Largest distance from a point of `a` (segment ends) to the path `b` (a 1 mm grid of b's
// segments keeps this linear).
inline double max_distance_mm(const CutPath& a, const CutPath& b) {
  std::map<std::pair<int, int>, std::vector<size_t>> grid;
  for (size_t i = 0; i < b.segs.size(); ++i) {
    const CutPath::Seg& s = b.segs[i];
    for (int gx = int(std::floor(std::min(s.x0, s.x1)));
         gx <= int(std::floor(std::max(s.x0, s.x1))); ++gx)
      for (int gy = int(std::floor(std::min(s.y0, s.y1)));
           gy <= int(std::floor(std::max(s.y0, s.y1))); ++gy)
        grid[{gx, gy}].push_back(i);
  }
  double worst = 0;
  for (const CutPath::Seg& s : a.segs) {
    for (const auto& [x, y] : {std::pair{s.x0, s.y0}, std::pair{s.x1, s.y1}}) {
      double best = 1e9;
      const int gx = int(std::floor(x)), gy = int(std::floor(y));
      for (int ix = gx - 1; ix <= gx + 1; ++ix)
        for (int iy = gy - 1; iy <= gy + 1; ++iy) {
          auto it = grid.find({ix, iy});
          if (it == grid.end()) continue;
          for (size_t k : it->second) best = std::min(best, point_segment_mm(x, y, b.segs[k]));
        }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

// Both lists of segments, one after the other (a job cut on two machines).
inline CutPath joined(CutPath a, const CutPath& b) {
  a.segs.insert(a.segs.end(), b.segs.begin(), b.segs.end());
  a.length_mm += b.length_mm;
  return a;
}

}  // namespace host::test

#endif  // HOST_TESTS_HOST_SIM_CUT_PATH_H
