// The probe area of a board job (board_probe_area.h).
#include "host/lib/pcb/board_probe_area.h"

#include <algorithm>  // std::min, std::max

#include "host/lib/heightmap/job_area.h"  // cutting_area
#include "host/lib/pcb/cutout.h"          // CutoutError

namespace host::pcb {

namespace {

void grow(heightmap::AreaMm* a, const heightmap::AreaMm& b) {
  a->x0 = std::min(a->x0, b.x0);
  a->y0 = std::min(a->y0, b.y0);
  a->x1 = std::max(a->x1, b.x1);
  a->y1 = std::max(a->y1, b.y1);
}

heightmap::AreaMm mirrored(const heightmap::AreaMm& a, double axis_x_mm) {
  return {2 * axis_x_mm - a.x1, a.y0, 2 * axis_x_mm - a.x0, a.y1};
}

// What the bottom side cuts (machine frame, the nominal placement); nullopt when it cuts
// nothing or cannot be planned (its own upload says why).
std::optional<heightmap::AreaMm> bottom_side_area(const BoardLayers& layers,
                                                  const BoardOptions& top_options) {
  BoardOptions o = top_options;
  o.side = BoardSide::kBottom;
  o.alignment.placement = RigidTransform();
  try {
    return heightmap::cutting_area(plan_board(layers, o).plan);
  } catch (const PlanError&) {
    return std::nullopt;
  } catch (const CutoutError&) {
    return std::nullopt;
  }
}

}  // namespace

double flip_axis_machine_x_mm(const BoardJob& job) {
  return job.frame.sx * job.flip_axis_file_x_mm + job.frame.offset_mm.x();
}

std::optional<heightmap::AreaMm> board_probe_area(const BoardLayers& layers,
                                                  const BoardOptions& options,
                                                  const BoardJob& job) {
  const std::optional<heightmap::AreaMm> top = heightmap::cutting_area(job.plan);
  if (!top || options.side != BoardSide::kTop || job.alignment_holes_mm.empty()) return top;
  const double axis_x_mm = flip_axis_machine_x_mm(job);
  heightmap::AreaMm area = *top;
  if (const std::optional<heightmap::AreaMm> bottom = bottom_side_area(layers, options)) {
    grow(&area, *bottom);
    grow(&area, mirrored(*bottom, axis_x_mm));
  }
  if (!layers.copper_bottom) grow(&area, mirrored(*top, axis_x_mm));
  area.x0 = std::max(0.0, area.x0);  // a job at the zero corner: never below X 0
  return area;
}

}  // namespace host::pcb
