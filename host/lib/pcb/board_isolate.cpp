// The board planner's isolation stage (see board_stages.h).
#include "host/lib/pcb/board_stages.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min, std::max, std::stable_sort
#include <cmath>      // std::ceil
#include <stdexcept>  // std::invalid_argument

#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/counted.h"       // counted: "1 hole", "2 holes"
#include "host/lib/plan/job_defaults.h"  // kToolWidthRangeMm

namespace host::pcb::board_stages {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

std::vector<Point2> polyline_mm(const Path& p, double sx) {
  std::vector<Point2> out;
  for (const IntPoint& q : p) {
    const Point2 m = to_mm(q);
    out.emplace_back(sx * m.x(), m.y());
  }
  return out;
}

double polyline_length(const std::vector<Point2>& p, bool closed) {
  double l = 0;
  for (size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  if (closed && p.size() > 1) l += (p.front() - p.back()).norm();
  return l;
}

namespace {

// The largest whole micrometre below mm (mm itself excluded).
double micrometre_below(double mm) {
  return (std::ceil(mm * 1000 - 1e-6) - 1) / 1000;
}

// What to do, with the widest tool that passes the narrowest gap with its clearance (to the
// micrometre below, and with kNarrowGapRoomNm to spare: a tool exactly as wide was refused
// in its turn): the user need not guess it (example_board: 0.057 mm -> 0.041 mm); and,
// where the tool itself fits the gap, the clearance that passes with this tool.
std::string narrow_gap_advice(const std::vector<NarrowGap>& gaps, const IsolationOptions& io) {
  double narrowest_mm = gaps.front().gap_mm;
  for (const NarrowGap& g : gaps) narrowest_mm = std::min(narrowest_mm, g.gap_mm);
  const double clearance_mm = std::max(0.0, io.clearance_mm);
  const double room_mm = kNarrowGapRoomNm / kNmPerMm;
  const double fits_mm = micrometre_below(narrowest_mm - 2 * clearance_mm - room_mm);
  const double clearance_fits_mm =
      micrometre_below((narrowest_mm - io.tool_width_mm - room_mm) / 2);
  // A sentence of its own after either advice.
  const std::string smaller_clearance =
      clearance_fits_mm >= 0 && clearance_fits_mm < clearance_mm
          ? fmt::format(
                " Or keep the tool and lower the clearance: --clearance {:.3f} passes every gap "
                "(the clearance is the room kept between the tool's edge and the copper for the "
                "curve fit and the machine's contour error; with less, the checks may find the "
                "tool in the copper).",
                clearance_fits_mm)
          : std::string();
  if (fits_mm < defaults::kToolWidthRangeMm.min)
    return "Plan anyway (--allow-narrow-gaps: the copper at those gaps stays joined); no tool of "
           "at least " +
           fmt::format("{:g} mm passes the narrowest gap ({:.3f} mm) with 2 x {} mm clearance.{}",
                       defaults::kToolWidthRangeMm.min, narrowest_mm, mm_text(clearance_mm),
                       smaller_clearance);
  return fmt::format(
      "Use a narrower tool: --tool-width {:.3f} passes every gap (the narrowest, {:.3f} mm, less "
      "2 x {} mm clearance), or plan anyway (--allow-narrow-gaps: the copper at "
      "those gaps stays joined).{}",
      fits_mm, narrowest_mm, mm_text(clearance_mm), smaller_clearance);
}

}  // namespace

std::vector<Trace> isolate(const BoardLayers& layers, const PcbLayer* copper,
                           const std::vector<Island>& islands, const BoardOptions& o, double sx,
                           BoardJob& job) {
  BoardReport& rep = job.report;
  std::vector<Trace> iso;
  IsolationResult iso_result;
  IsolationOptions io = o.isolation;
  if (io.mill_all && io.area_nm.empty() && layers.outline) {
    io.area_nm = plan_cutout(*layers.outline, o.cutout).board_nm;
  }
  try {
    iso_result = plan_isolation(islands, io);
  } catch (const std::invalid_argument& e) {
    throw PlanError(e.what());
  }
  rep.islands = iso_result.islands;
  rep.narrow_gaps = iso_result.narrow_gaps;
  if (iso_result.empty_holes_skipped > 0)
    rep.notes.push_back(
        fmt::format("{}: {} in the copper {} no other island (a hatched pour): no contour "
                    "inside {} (--isolate-empty-holes cuts {})",
                    copper->path, counted(iso_result.empty_holes_skipped, "opening"),
                    iso_result.empty_holes_skipped == 1 ? "holds" : "hold",
                    iso_result.empty_holes_skipped == 1 ? "it" : "them",
                    iso_result.empty_holes_skipped == 1 ? "it" : "them"));
  if (!rep.narrow_gaps.empty() && !o.allow_narrow_gaps) {
    std::string msg = fmt::format(
        "{}: {} where the copper is no farther apart than the tool width {} mm plus twice its "
        "clearance, so the tool cannot pass between the islands with that room:",
        copper->path, counted(rep.narrow_gaps.size(), "place"), mm_text(io.tool_width_mm));
    // The narrowest first (outside tester 21: the 20 listed of 105 were in island order, and
    // none was the gap the advice below quotes); the report keeps island order.
    std::vector<NarrowGap> narrowest = rep.narrow_gaps;
    std::stable_sort(narrowest.begin(), narrowest.end(),
                     [](const NarrowGap& a, const NarrowGap& b) { return a.gap_mm < b.gap_mm; });
    for (size_t i = 0; i < narrowest.size() && i < 20; ++i)
      msg += "\n  " + describe_gap(narrowest[i], io);
    if (narrowest.size() > 20)
      msg += fmt::format(
          "\n  ... and {} wider (--allow-narrow-gaps plans anyway and lists them all in the "
          "report)",
          narrowest.size() - 20);
    msg += "\n" + narrow_gap_advice(rep.narrow_gaps, io);
    throw PlanError(msg);
  }
  FitOptions fo;
  fo.tolerance_mm = o.fit_tolerance_mm;
  for (size_t i = 0; i < iso_result.paths.size(); ++i) {
    const ToolPathNm& t = iso_result.paths[i];
    const std::vector<Point2> pts = polyline_mm(t.path, sx);
    if (pts.size() < 2) continue;
    Trace tr;
    tr.curves = fit_polyline(pts, t.closed, fo, &rep.fit);
    if (tr.curves.empty()) continue;
    tr.source = fmt::format("{} contour {} (pass {})", t.clearing ? "clearing" : "isolation", i,
                            t.pass + 1);
    tr.clearing = t.clearing;
    rep.isolation_vertices += t.path.size() + (t.closed ? 1 : 0);
    rep.isolation_length_mm += polyline_length(pts, t.closed);
    iso.push_back(tr);
  }
  rep.isolation_contours = iso.size();
  job.tool_radius_mm = iso_result.tool_radius_mm;
  job.clearing_tool_radius_mm = iso_result.clearing_tool_radius_mm;
  return iso;
}

}  // namespace host::pcb::board_stages
