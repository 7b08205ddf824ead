// The planned board's isolation check and the refusal of a job that cuts copper (see
// board_check.h).
#include "host/lib/pcb/board_check.h"

#include <fmt/format.h>  // fmt::format

#include "host/lib/plan/counted.h"          // counted: "1 hole", "2 holes"
#include "host/lib/plan/firmware_points.h"  // firmware_points_mm

namespace host::pcb {

namespace {

// The clearing tool's paths swept by its own radius: its copper hits join the check's (the
// islands are separated by the isolation tool's passes, which go round every one).
void add_clearing_hits(const BoardJob& job, const std::vector<std::vector<Point2>>& paths,
                       const BoardOptions& o, IsolationCheck* c) {
  if (paths.empty()) return;
  const IsolationCheck w = check_isolation(job.copper_machine, paths, job.clearing_tool_radius_mm,
                                           isolation_check_tolerance_mm(o));
  c->hits.insert(c->hits.end(), w.hits.begin(), w.hits.end());
}

}  // namespace

double isolation_check_tolerance_mm(const BoardOptions& o) {
  return o.fit_tolerance_mm + 0.001;
}

IsolationCheck check_planned_isolation(const BoardJob& job, const BoardOptions& o) {
  if (job.copper_machine.empty()) return IsolationCheck{};
  IsolationCheck c = check_isolation(job.copper_machine, job.isolation_paths_mm, job.tool_radius_mm,
                                     isolation_check_tolerance_mm(o));
  add_clearing_hits(job, job.clearing_paths_mm, o, &c);
  return c;
}

IsolationCheck check_controller_isolation(const BoardJob& job, const BoardOptions& o,
                                          int chord_tolerance_um) {
  if (job.copper_machine.empty()) return IsolationCheck{};
  std::vector<std::vector<Point2>> paths;
  paths.reserve(job.isolation_curves);
  for (size_t i = 0; i < job.isolation_curves; ++i)
    paths.push_back(firmware_points_mm(job.plan.curves[i].spline(), chord_tolerance_um));
  IsolationCheck c = check_isolation(job.copper_machine, paths, job.tool_radius_mm,
                                     isolation_check_tolerance_mm(o));
  std::vector<std::vector<Point2>> clearing;
  for (size_t i = job.isolation_curves; i < job.isolation_curves + job.clearing_curves; ++i)
    clearing.push_back(firmware_points_mm(job.plan.curves[i].spline(), chord_tolerance_um));
  add_clearing_hits(job, clearing, o, &c);
  return c;
}

void refuse_copper_hits(const IsolationCheck& c, const std::string& paths) {
  if (c.hits.empty()) return;
  throw CopperCutError(
      fmt::format("the job would cut copper: {} cut into copper in {} (a larger clearance, a "
                  "finer chord tolerance or a narrower tool keeps the tool off it): {}",
                  paths, counted(c.hits.size(), "place"), describe(c)));
}

}  // namespace host::pcb
