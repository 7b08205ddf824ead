// The cutting area of a job against its height map (job_area.h).
#include "host/lib/heightmap/job_area.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min

namespace host::heightmap {

std::optional<AreaMm> cutting_area(const JobPlan& plan) {
  Extents e = plan.extents_mm;
  for (const PlanStep& s : plan.steps)
    if (s.kind == PlanStep::kFeed || s.kind == PlanStep::kDrill)
      e.add(Point2(s.to.x_um / 1000.0, s.to.y_um / 1000.0));
  if (e.empty()) return std::nullopt;
  return AreaMm{e.min.x(), e.min.y(), e.max.x(), e.max.y()};
}

void refuse_job_outside_map(const JobPlan& plan, const HeightMap& map, const std::string& what) {
  const std::optional<AreaMm> a = cutting_area(plan);
  if (!a) return;
  if (map.covers(a->x0, a->y0) && map.covers(a->x1, a->y1)) return;
  throw HeightMapError(fmt::format(
      "{}: the job cuts over ({:.3f}, {:.3f}) .. ({:.3f}, {:.3f}) mm, the map covers only "
      "({:.3f}, {:.3f}) .. ({:.3f}, {:.3f}) mm: probe again over this job (--probe), the job "
      "was not started",
      what, a->x0, a->y0, a->x1, a->y1, map.origin_x_mm, map.origin_y_mm, map.max_x_mm(),
      map.max_y_mm()));
}

}  // namespace host::heightmap
