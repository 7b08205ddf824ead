// The board job planner (see board_job.h).
#include "host/lib/pcb/board_job.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::max
#include <cmath>      // std::pow, std::round, std::fabs
#include <utility>    // std::move

#include "host/lib/pcb/board_stages.h"

namespace host::pcb {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

void check_options(const BoardOptions& o) {
  if (!(o.isolation_depth_mm > 0)) throw PlanError("the isolation depth must be positive");
  if (!(o.drill_depth_mm > 0) || !(o.cutout_depth_mm > 0) || !(o.cutout_step_mm > 0))
    throw PlanError("drill depth, cut-out depth and cut-out step must be positive");
  if (!(o.feed_mm_per_s > 0) || !(o.plunge_mm_per_s > 0) || !(o.drill_feed_mm_per_s > 0) ||
      !(o.cutout_feed_mm_per_s > 0))
    throw PlanError("feeds must be positive");
  if (!(o.z_travel_mm > 0) || !(o.drill_start_mm > 0))
    throw PlanError("the travel height and the drill start height must be above the board");
  const CutoutOptions& c = o.cutout;  // no tab cut: no height for one to keep
  const bool tabs_cut = c.tab_width_mm > 0 && (c.tab_count > 0 || c.tab_spacing_mm > 0);
  if (tabs_cut && !(o.tab_height_mm >= 0 && o.tab_height_mm < o.cutout_depth_mm))
    throw PlanError("the tab height must be below the cut-out depth");
  check_work_area(o.work_width_mm, o.work_height_mm, o.travel_width_mm, o.travel_height_mm);
}

}  // namespace

namespace board_stages {

const PcbLayer* read_layers(const BoardLayers& given, const BoardOptions& o, BoardLayers* out,
                            BoardJob& job) {
  check_options(o);
  BoardReport& rep = job.report;
  BoardLayers& layers = *out;
  layers = given;
  if (layers.outline && layers.outline->polygons_nm.empty()) {
    // KiCad writes an Edge.Cuts file holding only its aperture list when no outline is drawn.
    rep.notes.push_back(layers.outline->path +
                        ": the outline layer draws nothing: planned without a cut-out");
    layers.outline = nullptr;
  }
  const double sx = o.side == BoardSide::kBottom ? -1.0 : 1.0;
  job.frame.sx = sx;
  const PcbLayer* copper = o.side == BoardSide::kBottom ? layers.copper_bottom : layers.copper_top;
  if (!copper && !layers.drill && !layers.outline)
    throw PlanError(o.side == BoardSide::kBottom
                        ? "nothing to do: no bottom copper, drill or outline layer given"
                        : "nothing to do: no top copper, drill or outline layer given");
  return copper;
}

}  // namespace board_stages

Paths BoardFrame::to_machine_nm(const Paths& file_nm) const {
  Paths out;
  if (!placement.identity()) {
    for (const Path& p : file_nm) {
      Path q;
      for (const IntPoint& v : p) {
        const Point2 m = to_machine(to_mm(v));
        q.emplace_back(nm_from_mm(m.x()), nm_from_mm(m.y()));
      }
      if (sx < 0) ClipperLib::ReversePath(q);  // mirroring flips orientation: restore it
      out.push_back(q);
    }
    return out;
  }
  const ClipperLib::cInt ox = nm_from_mm(offset_mm.x()), oy = nm_from_mm(offset_mm.y());
  for (const Path& p : file_nm) {
    Path q;
    for (const IntPoint& v : p) q.emplace_back(sx < 0 ? -v.X + ox : v.X + ox, v.Y + oy);
    if (sx < 0) ClipperLib::ReversePath(q);  // mirroring flips orientation: restore it
    out.push_back(q);
  }
  return out;
}

namespace {

// The decimals that show `mm` as it is (3 to 6: micrometres to nanometres).
int mm_decimals(double mm) {
  for (int d = 3; d < 6; ++d) {
    const double scaled = mm * std::pow(10.0, d);
    if (std::fabs(scaled - std::round(scaled)) < 1e-6) return d;
  }
  return 6;
}

}  // namespace

std::string mm_text(double mm) {
  return fmt::format("{:.{}f}", mm, mm_decimals(mm));
}

std::string describe_gap(const NarrowGap& g, const IsolationOptions& o) {
  const double need_mm = o.tool_width_mm + 2 * std::max(0.0, o.clearance_mm);
  // Enough digits that the gap and the need differ as printed (the gap is narrower); a gap
  // as wide as the need (to kNarrowGapRoomNm) is said to be so.
  const bool narrower = g.gap_mm < need_mm - 1e-7;
  int d = mm_decimals(need_mm);
  while (narrower && d < 9 &&
         fmt::format("{:.{}f}", g.gap_mm, d) == fmt::format("{:.{}f}", need_mm, d))
    ++d;
  const std::string need =
      o.clearance_mm > 0 ? fmt::format("{:.{}f} mm (tool {} mm + 2 x {} mm clearance)", need_mm, d,
                                       mm_text(o.tool_width_mm), mm_text(o.clearance_mm))
                         : fmt::format("tool {:.{}f} mm", o.tool_width_mm, d);
  // In the files' frame, as the EDA tool shows the board (the isolation check's places are
  // the machine's: each says which).
  return fmt::format(
      "gap {:.{}f} mm {} {}{} between islands {} and {} at ({:.3f}, {:.3f}) mm in "
      "the files",
      g.gap_mm, d, narrower ? "<" : "=", need, narrower ? "" : ", no room to spare,", g.island_a,
      g.island_b, g.at.x / kNmPerMm, g.at.y / kNmPerMm);
}

std::string tool_label(const char* what, double diameter_mm) {
  std::string s = fmt::format("{} {:.2f}mm", what, diameter_mm);
  if (s.size() > 16) s = fmt::format("{:.2f}mm", diameter_mm);
  return s.substr(0, 16);
}

BoardJob plan_board(const BoardLayers& given, const BoardOptions& o) {
  using namespace board_stages;  // NOLINT(google-build-using-namespace): the stages, in order
  BoardJob job;
  BoardLayers layers;
  const PcbLayer* copper = read_layers(given, o, &layers, job);
  const double sx = job.frame.sx;
  // The copper's islands once: isolation, holes on copper, and the checks in the machine frame.
  std::vector<Island> islands;
  std::vector<Trace> iso;
  if (copper) {
    islands = copper_islands(copper->polygons_nm);
    iso = isolate(layers, copper, islands, o, sx, job);
  }
  std::vector<DrillTool> drills;
  if (layers.drill) drills = drill(layers, copper, islands, o, sx, job.report);
  CutoutPlan cp;
  std::vector<Trace> cut;
  if (layers.outline)
    cut = cut_out(layers, o, sx, cp, job);
  else
    job.report.no_cutout = given.outline ? "the outline layer draws nothing" : "no outline layer";
  Extents region;  // double-sided: one frame for both setups
  if (o.alignment.enabled) region = align_sides(layers, copper, cp, o, sx, drills, cut, job);
  const Point2 offset = place(iso, cut, drills, region, o, job);
  write_steps(iso, cut, drills, offset, o, job);
  machine_frame_geometry(layers, copper, std::move(islands), cp, job);
  return job;
}

}  // namespace host::pcb
