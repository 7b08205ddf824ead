// Height maps of board jobs (see board_height_map.h).
#include "host/lib/server/board_height_map.h"

#include <algorithm>  // std::min, std::max

#include "host/lib/heightmap/job_area.h"  // cutting_area

namespace host::server {

const char kHeightMapFile[] = "heightmap.json";
const char kHeightMapMachineFile[] = "heightmap.machine";
const char kHeightMapPicture[] = "heightmap.svg";

namespace {

void grow(heightmap::AreaMm* a, double x0, double y0, double x1, double y1) {
  a->x0 = std::min(a->x0, x0);
  a->y0 = std::min(a->y0, y0);
  a->x1 = std::max(a->x1, x1);
  a->y1 = std::max(a->y1, y1);
}

}  // namespace

std::optional<heightmap::AreaMm> board_probe_area(const pcb::BoardJob& job) {
  std::optional<heightmap::AreaMm> area = heightmap::cutting_area(job.plan);
  if (!area || job.alignment_holes_mm.empty()) return area;
  // The board's outline and its cut-out, which the bottom job cuts.
  const double r = job.cutter_radius_mm;
  for (const ClipperLib::Path& path : job.board_machine_nm) {
    for (const ClipperLib::IntPoint& p : path) {
      const double x = p.X / pcb::kNmPerMm, y = p.Y / pcb::kNmPerMm;
      grow(&*area, x - r, y - r, x + r, y + r);
    }
  }
  // The mirror about the flip axis (machine frame: the holes stand on it).
  const double a = job.alignment_holes_mm.front().x();
  grow(&*area, 2 * a - area->x1, area->y0, 2 * a - area->x0, area->y1);
  area->x0 = std::max(0.0, area->x0);  // a job at the zero corner: never below X 0
  return area;
}

nlohmann::json area_json(const heightmap::AreaMm& a) {
  return {a.x0, a.y0, a.x1, a.y1};
}

heightmap::AreaMm area_of_json(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>(),
          j.at(3).get<double>()};
}

heightmap::HeightMap map_after_flip(const heightmap::HeightMap& top, double flip_axis_x_mm,
                                    const std::string& flip) {
  if (flip == "table") return top;
  if (flip != "blank")
    throw heightmap::HeightMapError("height_map_flip '" + flip + "': table or blank");
  heightmap::HeightMap m = top;
  const double a = flip_axis_x_mm;
  // Column c of the new grid lies at 2a - x(cols - 1 - c) of the old one.
  m.origin_x_mm = 2 * a - top.max_x_mm();
  const double zero_um = top.interpolate_um(2 * a, 0.0);
  for (int row = 0; row < top.rows; ++row) {
    for (int col = 0; col < top.cols; ++col) {
      m.heights_um[row * m.cols + col] = -(top.height_um(row, top.cols - 1 - col) - zero_um);
    }
  }
  heightmap::validate(m, "the flipped map");
  return m;
}

}  // namespace host::server
