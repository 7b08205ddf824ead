// The board planner's last stage: the machine-frame geometry for the checks and the plot (see
// board_stages.h).
#include "host/lib/pcb/board_stages.h"

#include <utility>  // std::move

#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/firmware_spline.h"

namespace host::pcb::board_stages {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

void machine_frame_geometry(const BoardLayers& layers, const PcbLayer* copper,
                            std::vector<Island> islands, const CutoutPlan& cp, BoardJob& job) {
  const JobPlan& plan = job.plan;
  if (copper) {
    if (job.frame.placement.identity()) {
      // Mirrored and shifted by whole nanometres: the same islands, exactly.
      for (Island& island : islands) {
        island.paths = job.frame.to_machine_nm(island.paths);
        island.box = BoxNm();
        island.box.add(island.paths[0]);
      }
      job.copper_machine = std::move(islands);
    } else {
      // Turned and rounded to the nanometre (a measured alignment): united afresh.
      job.copper_machine = copper_islands(job.frame.to_machine_nm(copper->polygons_nm));
    }
    for (size_t i = 0; i < job.isolation_curves + job.clearing_curves; ++i) {
      std::vector<std::vector<Point2>>& paths =
          i < job.isolation_curves ? job.isolation_paths_mm : job.clearing_paths_mm;
      std::vector<Point2> pts;
      for (const PlanStep& s : plan.steps) {
        if (s.kind != PlanStep::kSpline || s.curve != static_cast<int>(i)) continue;
        const std::vector<Point2> piece =
            sample(from_firmware_spline(s.spline().firmware()), 0.0005);
        pts.insert(pts.end(), piece.begin() + (pts.empty() ? 0 : 1), piece.end());
      }
      if (plan.curves[i].chained && !paths.empty()) {
        std::vector<Point2>& last = paths.back();
        last.insert(last.end(), pts.begin() + (pts.empty() ? 0 : 1), pts.end());
      } else {
        paths.push_back(pts);
      }
    }
  }
  if (layers.drill) {
    for (const Hole& h : layers.drill->holes) {
      Hole m = h;
      const Point2 p = job.frame.to_machine(to_mm(IntPoint(h.at.x, h.at.y)));
      m.at.x = nm_from_mm(p.x());
      m.at.y = nm_from_mm(p.y());
      job.holes_machine.push_back(m);
    }
    for (const Slot& s : layers.drill->slots) {
      Slot m = s;
      const Point2 a = job.frame.to_machine(to_mm(IntPoint(s.from.x, s.from.y)));
      const Point2 b = job.frame.to_machine(to_mm(IntPoint(s.to.x, s.to.y)));
      m.from.x = nm_from_mm(a.x()), m.from.y = nm_from_mm(a.y());
      m.to.x = nm_from_mm(b.x()), m.to.y = nm_from_mm(b.y());
      job.slots_machine.push_back(m);
    }
  }
  if (layers.outline) job.board_machine_nm = union_of(job.frame.to_machine_nm(cp.board_nm));
  const size_t first_cutout = job.isolation_curves + job.clearing_curves;
  for (size_t i = first_cutout; i < plan.curves.size(); ++i) {
    if (plan.curves[i].source == "hole" || plan.curves[i].source == "slot") continue;
    const std::vector<Point2> pts = sample(plan.curves[i].spline(), 0.002);
    if (plan.curves[i].chained && !job.cutout_paths_mm.empty() && i > first_cutout) {
      std::vector<Point2>& last = job.cutout_paths_mm.back();
      last.insert(last.end(), pts.begin() + 1, pts.end());
    } else {
      job.cutout_paths_mm.push_back(pts);
    }
  }
}

}  // namespace host::pcb::board_stages
