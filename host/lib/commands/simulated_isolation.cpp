// The simulated tool path of a board run against its copper (see simulated_isolation.h).
#include "host/lib/commands/simulated_isolation.h"

#include <algorithm>  // std::min, std::max
#include <limits>     // std::numeric_limits

#include "host/lib/sim/contour_error.h"  // NearestSegment

namespace host::commands {

namespace {

// The least clearance of the tool's edge (um) over points, and where: each point's distance
// to the copper's edges less the radius. That distance changes no faster than the point
// moves, so a point nearer to the last one measured than that one's distance less the least
// so far cannot go below it and is not measured (half of eaglecad1's simulated samples; an
// isolation path keeps within a few um of its least clearance, so few of its planned ones).
class LeastClearance {
 public:
  LeastClearance(const sim::NearestSegment& copper, double radius_mm)
      : copper_(copper), radius_mm_(radius_mm) {}
  void add(const Point2& p) {
    // 1e-6 um: rounding never lets a point skipped here be the least.
    if (measured_ && (known_mm_ - (p - known_at_).norm() - radius_mm_) * 1000.0 > least_um + 1e-6) {
      return;
    }
    known_mm_ = copper_.distance(p);
    known_at_ = p;
    measured_ = true;
    const double c = (known_mm_ - radius_mm_) * 1000.0;
    if (c < least_um) {
      least_um = c;
      at_mm = p;
    }
  }
  double least_um = std::numeric_limits<double>::infinity();
  Point2 at_mm{0, 0};

 private:
  const sim::NearestSegment& copper_;
  double radius_mm_;
  bool measured_ = false;
  double known_mm_ = 0;
  Point2 known_at_{0, 0};
};

}  // namespace

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
  LeastClearance narrow(copper, job.tool_radius_mm);
  for (const std::vector<Point2>& path : narrow_cuts)
    for (const Point2& p : path) narrow.add(p);
  s.min_clearance_um = narrow.least_um;
  s.min_clearance_at_mm = narrow.at_mm;
  if (!job.clearing_paths_mm.empty()) {
    LeastClearance wide(copper, job.clearing_tool_radius_mm);
    for (const std::vector<Point2>& path : wide_cuts)
      for (const Point2& p : path) wide.add(p);
    s.clearing_min_clearance_um = wide.least_um;
  }
  LeastClearance planned(copper, job.tool_radius_mm);
  for (const std::vector<Point2>& path : job.isolation_paths_mm) {
    for (size_t i = 0; i < path.size(); ++i) {
      const Point2 a = path[i], b = i + 1 < path.size() ? path[i + 1] : a;
      const int n = 1 + static_cast<int>((b - a).norm() / 0.005);
      for (int k = 0; k < n; ++k) planned.add(a + (b - a) * (double(k) / n));
    }
  }
  s.planned_min_clearance_um = planned.least_um;
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
