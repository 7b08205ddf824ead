// Isolation routing: tool-centre contours around every copper island for a tool of a given
// width, further passes with overlap, optionally clearing all copper-free area; gaps the
// tool cannot pass through are found and reported, never silently merged.
#ifndef HOST_LIB_PCB_ISOLATION_H
#define HOST_LIB_PCB_ISOLATION_H

#include <clipper.hpp>  // ClipperLib::Paths

#include <vector>  // std::vector

#include "host/lib/pcb/pcb_geometry.h"  // Island
#include "host/lib/pcb/pcb_layer.h"
#include "host/lib/plan/job_defaults.h"

namespace host::pcb {

struct IsolationOptions {
  double tool_width_mm = defaults::kToolWidthMm;  // a V-bit's width at the cutting depth
  int passes = defaults::kPasses;                 // contours per island, each farther out
  double overlap =
      defaults::kOverlap;           // fraction of the tool width a pass overlaps the previous one
  bool mill_all = false;            // keep offsetting until the whole copper-free area is cleared
  ClipperLib::Paths area_nm;        // mill_all: the area to clear (the board); empty: the copper's
                                    // bounds grown by two tool widths
  double arc_tolerance_mm = 0.001;  // chord error of Clipper's round joins
  // Kept between the tool's edge and the copper on top of the tool radius (why: job_defaults.h).
  // Narrow gaps are judged with it too.
  double clearance_mm = defaults::kClearanceMm;
  // A wider tool for the outer part of the isolation (pcb2gcode's mill-diameters list): the
  // first narrow_passes passes are cut with the tool above next to the copper, the rest of the
  // width `passes` narrow passes would clear with this one. 0: none.
  double clearing_tool_width_mm = 0;
  int narrow_passes = 1;
  // A hole in an island that holds no other island (a hatched pour's opening) separates
  // nothing: no contour is cut inside it unless this is set. mill_all clears them anyway.
  bool isolate_empty_holes = false;
};

// Two islands closer than the tool width plus twice the clearance: the tool cannot pass
// between them with its clearance to both.
struct NarrowGap {
  PointNm at;           // the narrowest place: the middle of the shortest line between them
  double gap_mm = 0;    // smallest distance between the two islands (from their vertices)
  size_t island_a = 0;  // indices into IsolationResult::islands order
  size_t island_b = 0;
};

struct ToolPathNm {
  ClipperLib::Path path;
  bool closed = true;
  int pass = 0;           // 0: the contour next to the copper
  bool clearing = false;  // cut with the clearing tool
};

struct IsolationResult {
  std::vector<ToolPathNm> paths;  // pass 0 first; the clearing tool's last
  std::vector<NarrowGap> narrow_gaps;
  size_t islands = 0;
  size_t empty_holes_skipped = 0;  // holes left uncut (IsolationOptions::isolate_empty_holes)
  double tool_radius_mm = 0;
  double clearing_tool_radius_mm = 0;  // 0: no clearing paths
};

// How far from the copper the clearing tool's edge stays (mm): inside the band the narrow
// passes cut, overlapping their outer part by the overlap of one narrow pass, so the copper's
// edge is shaped by the narrow tool alone. 0 without a clearing tool.
double clearing_edge_distance_mm(const IsolationOptions& o);

// Plans the isolation of copper (Clipper polygons, nm). Throws std::invalid_argument for a
// non-positive tool width, passes < 1 or overlap outside [0, 0.9], a clearing tool not wider
// than the tool, or one with mill_all.
IsolationResult plan_isolation(const ClipperLib::Paths& copper_nm, const IsolationOptions& o);
// The same for copper already split into islands (copper_islands): the narrow gaps, the
// contours and the clearing rings all start from them.
IsolationResult plan_isolation(const std::vector<Island>& islands, const IsolationOptions& o);

// How much wider than the tool plus twice its clearance a gap must be (nm): where the two
// islands' clearances only touch, they are united into one contour round both, and the
// tool cannot separate them (two pads' flat sides exactly that far apart).
const double kNarrowGapRoomNm = 20;

// Islands (copper_islands()) whose tool clearances (copper grown by radius_nm) overlap: the
// narrow gaps.
std::vector<NarrowGap> find_narrow_gaps(const std::vector<Island>& islands, double radius_nm,
                                        double arc_tolerance_nm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_ISOLATION_H
