// The one resolver of board options (see board_args.h).
#include "host/lib/pcb/board_args.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>    // std::isfinite
#include <sstream>  // std::istringstream

namespace host::pcb {

namespace {

// Copper given only for the other side would leave a job without isolation that looks
// planned (holes and cut-out alone).
void refuse_other_side_copper(BoardSide side, const BoardFileSet& layers) {
  const bool bottom = side == BoardSide::kBottom;
  const std::vector<PcbLayer>& job_copper = bottom ? layers.copper_bottom : layers.copper_top;
  const std::vector<PcbLayer>& other_copper = bottom ? layers.copper_top : layers.copper_bottom;
  if (!job_copper.empty() || other_copper.empty()) return;
  const std::string name = bottom ? "bottom" : "top", other = bottom ? "top" : "bottom";
  throw BoardArgsError("the job's side is " + name + " but the copper given (" +
                       other_copper.front().path + ") is " + other +
                       " copper: nothing to isolate; give --side " + other + " or the " + name +
                       " copper");
}

}  // namespace

void refuse_option_combinations(const BoardArgs& a) {
  const BoardIsolationArgs& i = a.isolation;
  // First: no --passes makes these two go together (it was "give more --passes", and then
  // this, to a line with the default --passes).
  if (i.clearing_tool_mm > 0 && i.mill_all)
    throw BoardArgsError(
        "--clearing-tool cannot be combined with --mill-all (which clears all "
        "copper-free area with the isolation tool): give one of them");
  if (i.clearing_tool_mm > 0 && i.narrow_passes >= i.passes)
    throw BoardArgsError(
        fmt::format("--clearing-tool cuts the passes beyond --narrow-passes ({}), "
                    "but --passes is {}: give more --passes, or no clearing tool",
                    i.narrow_passes, i.passes));
  if (!(i.clearing_tool_mm > 0) && i.narrow_passes != 1)
    throw BoardArgsError(
        "--narrow-passes counts the isolation tool's passes next to "
        "the copper with a --clearing-tool: give the clearing tool");
  if (i.clearing_tool_mm > 0 && !(i.clearing_tool_mm > i.tool_width_mm))
    throw BoardArgsError(
        fmt::format("--clearing-tool ({} mm) must be wider than "
                    "--tool-width ({} mm): it cuts the outer passes",
                    i.clearing_tool_mm, i.tool_width_mm));
  // Only where tabs are cut: --tabs 0 or --tab-width 0 leaves no tab to keep a height.
  const BoardCutoutArgs& c = a.cutout;
  const bool tabs_cut = c.tab_width_mm > 0 && (c.tabs > 0 || c.tab_spacing_mm > 0);
  if (tabs_cut && !(c.tab_height_mm < c.depth_mm))
    throw BoardArgsError(
        fmt::format("--tab-height ({} mm) must be below --cut-depth "
                    "({} mm): a tab keeps part of the board",
                    c.tab_height_mm, c.depth_mm));
}

namespace {

AlignmentOptions alignment_options(const BoardAlignmentArgs& a) {
  AlignmentOptions o;
  if (a.holes.empty()) {
    if (!a.measured_mm.empty())
      throw BoardArgsError("--align-measured needs the job's --align-holes");
    return o;
  }
  o.enabled = true;
  o.hole_diameter_mm = a.diameter_mm;
  o.hole_depth_mm = a.depth_mm;
  const std::string why = parse_align_holes(a.holes, &o.holes_file_mm);
  if (!why.empty()) throw BoardArgsError(why);
  return o;
}

IsolationOptions isolation_options(const BoardIsolationArgs& a) {
  IsolationOptions o;
  o.tool_width_mm = a.tool_width_mm;
  o.passes = a.passes;
  o.overlap = a.overlap;
  o.clearance_mm = a.clearance_mm;
  o.mill_all = a.mill_all;
  o.clearing_tool_width_mm = a.clearing_tool_mm;
  o.narrow_passes = a.narrow_passes;
  o.isolate_empty_holes = a.isolate_empty_holes;
  return o;
}

}  // namespace

bool is_board_side(const std::string& side) {
  return side == "top" || side == "bottom";
}

std::string side_of_copper(const BoardFileSet& layers) {
  return layers.copper_top.empty() && !layers.copper_bottom.empty() ? "bottom" : "top";
}

BoardSide resolve_board_side(const std::string& asked, const std::string& prefix,
                             const BoardFileSet& layers) {
  std::string side = asked.empty() ? prefix : asked;
  if (side.empty()) side = side_of_copper(layers);
  if (!is_board_side(side))
    throw BoardArgsError("--side must be top or bottom, not '" + side + "'");
  return side == "bottom" ? BoardSide::kBottom : BoardSide::kTop;
}

std::string parse_align_holes(const std::string& text, std::vector<Point2>* holes_file_mm) {
  holes_file_mm->clear();
  if (text == "auto") return "";
  std::istringstream in(text);
  for (std::string xy; std::getline(in, xy, ';');) {
    double x = 0, y = 0;
    char comma = 0, extra = 0;
    std::istringstream one(xy);
    if (!(one >> x >> comma >> y) || comma != ',' || (one >> extra) || !std::isfinite(x) ||
        !std::isfinite(y)) {
      return "--align-holes: '" + xy +
             "' is not X,Y (mm, files' frame); holes are separated by ';', or say auto";
    }
    holes_file_mm->emplace_back(x, y);
  }
  if (holes_file_mm->empty()) return "--align-holes: no hole given (X,Y[;X,Y...] or auto)";
  return "";
}

BoardOptions resolve_board_options(const BoardArgs& a, const BoardMachine& m,
                                   const BoardFileSet& layers, const std::string& prefix_side) {
  BoardOptions o;
  o.side = resolve_board_side(a.side, prefix_side, layers);
  refuse_other_side_copper(o.side, layers);
  refuse_option_combinations(a);
  o.isolation = isolation_options(a.isolation);
  o.alignment = alignment_options(a.alignment);
  o.isolation_depth_mm = a.isolation.depth_mm;
  o.drill_depth_mm = a.drill.depth_mm;
  o.drill_start_mm = a.drill.start_mm;
  o.drill_feed_mm_per_s = a.drill.feed_mm_s;
  o.cutout.cutter_diameter_mm = a.cutout.cutter_mm;
  o.cutout.tab_width_mm = a.cutout.tab_width_mm;
  o.cutout.tab_count = a.cutout.tabs;
  o.cutout.tab_spacing_mm = a.cutout.tab_spacing_mm;
  o.cutout_depth_mm = a.cutout.depth_mm;
  o.cutout_step_mm = a.cutout.step_mm;
  o.cutout_feed_mm_per_s = a.cutout.feed_mm_s;
  o.tab_height_mm = a.cutout.tab_height_mm;
  o.spindle = !a.no_spindle;
  o.allow_narrow_gaps = a.allow_narrow_gaps;
  o.feed_mm_per_s = m.feed_mm_s;
  o.z_travel_mm = m.z_up_mm;
  o.margin_mm = m.margin_mm;
  o.work_width_mm = m.work_w_mm;
  o.work_height_mm = m.work_h_mm;
  return o;
}

}  // namespace host::pcb
