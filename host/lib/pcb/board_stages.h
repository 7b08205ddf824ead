// The board planner's stages (plan_board in board_job.cpp calls them in this order): read the
// layers, isolate the copper, drill, cut out, the two sides of a double-sided board, place the
// job, write its steps, and the machine-frame geometry its checks and plot need. Internal to
// host/lib/pcb.
#ifndef HOST_LIB_PCB_BOARD_STAGES_H
#define HOST_LIB_PCB_BOARD_STAGES_H

#include <string>   // std::string
#include <utility>  // std::pair
#include <vector>   // std::vector

#include "host/lib/pcb/board_job.h"

namespace host::pcb::board_stages {

// One traced path of the job before placement: fitted curves in the mirrored file frame.
struct Trace {
  std::vector<BSpline> curves;
  std::string source;
  std::vector<bool> lifted;  // cut-out: per curve, true over a tab
  bool clearing = false;     // isolation cut with the clearing tool
};

struct DrillTool {
  std::string label;
  double diameter_mm = 0;
  double depth_mm = 0;
  std::vector<Point2> holes;                     // mirrored file frame
  std::vector<std::pair<Point2, Point2>> slots;  // mirrored file frame
};

// The path in mm, x multiplied by sx (-1: mirrored for the bottom side).
std::vector<Point2> polyline_mm(const ClipperLib::Path& p, double sx);
double polyline_length(const std::vector<Point2>& p, bool closed);

// Read: checks the options, drops an outline layer that draws nothing, and returns this side's
// copper (nullptr: none); sets the job's mirror factor. PlanError when there is nothing to do.
const PcbLayer* read_layers(const BoardLayers& given, const BoardOptions& o, BoardLayers* layers,
                            BoardJob& job);
// Isolate: the copper's isolation contours fitted to curves (mirrored file frame); the report's
// islands, narrow gaps (a PlanError unless allowed) and the tools' radii.
// islands: the copper's (copper_islands), file frame.
std::vector<Trace> isolate(const BoardLayers& layers, const PcbLayer* copper,
                           const std::vector<Island>& islands, const BoardOptions& o, double sx,
                           BoardJob& job);
// Drill: holes grouped by tool and ordered, slots with their tool; holes on copper counted.
std::vector<DrillTool> drill(const BoardLayers& layers, const PcbLayer* copper,
                             const std::vector<Island>& islands, const BoardOptions& o, double sx,
                             BoardReport& rep);
// Cut out: the outline's loops as fitted curves, pieces over tabs marked lifted.
std::vector<Trace> cut_out(const BoardLayers& layers, const BoardOptions& o, double sx,
                           CutoutPlan& cp, BoardJob& job);
// Two sides: the alignment holes (drilled with the top side, which leaves the cut-out to the
// bottom side); returns the side-independent region placed at the margin.
Extents align_sides(const BoardLayers& layers, const PcbLayer* copper, const CutoutPlan& cp,
                    const BoardOptions& o, double sx, std::vector<DrillTool>& drills,
                    std::vector<Trace>& cut, BoardJob& job);
// Place: the tool's lower-left extent (or the region) at (margin, margin); PlanError when the
// job leaves the work area. Returns the offset.
Point2 place(const std::vector<Trace>& iso, const std::vector<Trace>& cut,
             const std::vector<DrillTool>& drills, const Extents& region, const BoardOptions& o,
             BoardJob& job);
// Steps: isolation (nearest start next), clearing, drilling, cut-out passes, home.
void write_steps(const std::vector<Trace>& iso, const std::vector<Trace>& cut,
                 const std::vector<DrillTool>& drills, const Point2& offset, const BoardOptions& o,
                 BoardJob& job);
// Check: what the checks and the plot need, in the machine frame (copper, the cut paths,
// holes, slots, board outline). islands: the copper's, file frame, taken over (numbered as
// the isolation's islands were).
void machine_frame_geometry(const BoardLayers& layers, const PcbLayer* copper,
                            std::vector<Island> islands, const CutoutPlan& cp, BoardJob& job);

}  // namespace host::pcb::board_stages

#endif  // HOST_LIB_PCB_BOARD_STAGES_H
