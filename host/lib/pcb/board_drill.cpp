// The board planner's drilling stage (see board_stages.h).
#include "host/lib/pcb/board_stages.h"

#include <cmath>  // std::llround

#include "host/lib/pcb/drill_order.h"
#include "host/lib/pcb/pcb_geometry.h"

namespace host::pcb::board_stages {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

std::vector<DrillTool> drill(const BoardLayers& layers, const PcbLayer* copper,
                             const std::vector<Island>& islands, const BoardOptions& o, double sx,
                             BoardReport& rep) {
  std::vector<DrillTool> drills;
  const PcbLayer& d = *layers.drill;
  std::vector<Point2> at;
  std::vector<double> dia;
  std::vector<int> tool;
  for (const Hole& h : d.holes) {
    const Point2 m = to_mm(IntPoint(h.at.x, h.at.y));
    at.emplace_back(sx * m.x(), m.y());
    dia.push_back(static_cast<double>(h.diameter_nm) / kNmPerMm);
    tool.push_back(h.tool);
  }
  rep.holes = at.size();
  rep.board_holes = at.size();
  if (copper) {
    // Alignment check: plated holes sit in pads.
    for (const Hole& h : d.holes) {
      const IntPoint c(h.at.x, h.at.y);
      for (const Island& is : islands) {
        if (c.X < is.box.min_x || c.X > is.box.max_x || c.Y < is.box.min_y || c.Y > is.box.max_y)
          continue;
        int inside = ClipperLib::PointInPolygon(c, is.paths[0]) != 0;
        for (size_t k = 1; k < is.paths.size() && inside; ++k)
          inside = ClipperLib::PointInPolygon(c, is.paths[k]) != 1;
        if (inside) {
          ++rep.holes_on_copper;
          break;
        }
      }
    }
  }
  rep.slots = d.slots.size();
  Extents ext;
  for (const Point2& p : at) ext.add(p);
  const DrillPlan dp = order_holes(at, dia, tool, ext.empty() ? Point2(0, 0) : ext.min);
  rep.drill_travel_file_order_mm = dp.travel_file_order_mm;
  rep.drill_travel_ordered_mm = dp.travel_ordered_mm;
  for (const DrillGroup& g : dp.groups) {
    DrillTool t;
    t.diameter_mm = g.diameter_mm;
    t.label = tool_label("Drill", g.diameter_mm);
    t.depth_mm = o.drill_depth_mm;
    t.holes = g.holes_mm;
    drills.push_back(t);
  }
  for (const Slot& s : d.slots) {
    const double dm = static_cast<double>(s.diameter_nm) / kNmPerMm;
    const Point2 a = to_mm(IntPoint(s.from.x, s.from.y)), b = to_mm(IntPoint(s.to.x, s.to.y));
    DrillTool* t = nullptr;
    for (DrillTool& x : drills)
      if (std::llround(x.diameter_mm * 1000) == std::llround(dm * 1000)) t = &x;
    if (!t) {
      drills.emplace_back();
      t = &drills.back();
      t->diameter_mm = dm;
      t->label = tool_label("Drill", dm);
      t->depth_mm = o.drill_depth_mm;
    }
    t->slots.emplace_back(Point2(sx * a.x(), a.y()), Point2(sx * b.x(), b.y()));
  }
  rep.drill_tools = drills.size();
  return drills;
}

}  // namespace host::pcb::board_stages
