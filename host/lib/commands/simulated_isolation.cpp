// The simulated tool path of a board run against its copper (see simulated_isolation.h).
#include "host/lib/commands/simulated_isolation.h"

#include <algorithm>  // std::min, std::max

#include "host/lib/sim/contour_error.h"  // NearestSegment

namespace host::commands {

SimulatedIsolation check_simulated_isolation(const pcb::BoardJob& job, double tolerance_mm,
                                             const std::vector<std::vector<Point2>>& cut_paths_mm,
                                             size_t samples) {
  SimulatedIsolation s;
  s.tolerance_mm = tolerance_mm;
  s.paths = cut_paths_mm.size();
  s.samples = samples;
  // With a clearing tool both tools cut at the isolation depth: a simulated path is the tool's
  // whose planned paths are nearer its middle sample, and is swept by that tool's radius.
  std::vector<std::vector<Point2>> narrow_cuts, wide_cuts;
  if (job.clearing_paths_mm.empty()) {
    narrow_cuts = cut_paths_mm;
  } else {
    const sim::NearestSegment narrow(job.isolation_paths_mm, 0.25);
    const sim::NearestSegment wide(job.clearing_paths_mm, 0.25);
    for (const std::vector<Point2>& path : cut_paths_mm) {
      if (path.empty()) continue;
      const Point2& m = path[path.size() / 2];
      (narrow.distance(m) <= wide.distance(m) ? narrow_cuts : wide_cuts).push_back(path);
    }
  }
  s.check =
      pcb::check_isolation(job.copper_machine, narrow_cuts, job.tool_radius_mm, s.tolerance_mm);
  if (!wide_cuts.empty()) {
    const pcb::IsolationCheck w = pcb::check_isolation(job.copper_machine, wide_cuts,
                                                       job.clearing_tool_radius_mm, s.tolerance_mm);
    s.check.hits.insert(s.check.hits.end(), w.hits.begin(), w.hits.end());
  }
  // Clearance: each sample's distance to the copper's edges less the tool radius (a sample
  // inside copper is a hit of the check above).
  std::vector<std::vector<Point2>> edges;
  for (const pcb::Island& island : job.copper_machine) {
    for (const ClipperLib::Path& p : island.paths) {
      std::vector<Point2> line;
      for (const ClipperLib::IntPoint& q : p) line.push_back(Point2(q.X * 1e-6, q.Y * 1e-6));
      if (!line.empty()) line.push_back(line.front());
      edges.push_back(std::move(line));
    }
  }
  const sim::NearestSegment copper(edges, 0.25);
  auto clearance_um = [&](const Point2& p, double radius_mm) {
    return (copper.distance(p) - radius_mm) * 1000.0;
  };
  s.min_clearance_um = std::numeric_limits<double>::infinity();
  for (const std::vector<Point2>& path : narrow_cuts) {
    for (const Point2& p : path) {
      const double c = clearance_um(p, job.tool_radius_mm);
      if (c < s.min_clearance_um) {
        s.min_clearance_um = c;
        s.min_clearance_at_mm = p;
      }
    }
  }
  if (!job.clearing_paths_mm.empty()) {
    s.clearing_min_clearance_um = std::numeric_limits<double>::infinity();
    for (const std::vector<Point2>& path : wide_cuts)
      for (const Point2& p : path)
        s.clearing_min_clearance_um =
            std::min(s.clearing_min_clearance_um, clearance_um(p, job.clearing_tool_radius_mm));
  }
  s.planned_min_clearance_um = std::numeric_limits<double>::infinity();
  for (const std::vector<Point2>& path : job.isolation_paths_mm) {
    for (size_t i = 0; i < path.size(); ++i) {
      const Point2 a = path[i], b = i + 1 < path.size() ? path[i + 1] : a;
      const int n = 1 + static_cast<int>((b - a).norm() / 0.005);
      for (int k = 0; k < n; ++k)
        s.planned_min_clearance_um =
            std::min(s.planned_min_clearance_um,
                     clearance_um(a + (b - a) * (double(k) / n), job.tool_radius_mm));
    }
  }
  return s;
}

Registration registration_error(const std::vector<std::vector<Point2>>& cut_paths_mm,
                                const pcb::RigidTransform& blank_error,
                                const std::vector<std::vector<Point2>>& nominal_paths_mm) {
  Registration r;
  if (nominal_paths_mm.empty()) return r;
  const sim::NearestSegment nominal(nominal_paths_mm, 0.25);
  const pcb::RigidTransform onto_board = blank_error.inverse();
  double sum = 0;
  for (const std::vector<Point2>& path : cut_paths_mm) {
    for (const Point2& p : path) {
      const double d_um = nominal.distance(onto_board.apply(p)) * 1000.0;
      r.max_um = std::max(r.max_um, d_um);
      sum += d_um;
      ++r.samples;
    }
  }
  r.mean_um = r.samples ? sum / static_cast<double>(r.samples) : 0;
  return r;
}

std::vector<std::vector<Point2>> isolation_paths_mm(const pcb::BoardJob& job) {
  std::vector<std::vector<Point2>> paths = job.isolation_paths_mm;
  paths.insert(paths.end(), job.clearing_paths_mm.begin(), job.clearing_paths_mm.end());
  return paths;
}

}  // namespace host::commands
