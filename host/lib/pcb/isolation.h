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
};

// Two islands closer than the tool width plus twice the clearance: the tool cannot pass
// between them with its clearance to both.
struct NarrowGap {
  PointNm at;           // middle of the region both islands' tool clearances cover
  double gap_mm = 0;    // smallest distance between the two islands (from their vertices)
  size_t island_a = 0;  // indices into IsolationResult::islands order
  size_t island_b = 0;
};

struct ToolPathNm {
  ClipperLib::Path path;
  bool closed = true;
  int pass = 0;  // 0: the contour next to the copper
};

struct IsolationResult {
  std::vector<ToolPathNm> paths;  // pass 0 first
  std::vector<NarrowGap> narrow_gaps;
  size_t islands = 0;
  double tool_radius_mm = 0;
};

// Plans the isolation of copper (Clipper polygons, nm). Throws std::invalid_argument for a
// non-positive tool width, passes < 1 or overlap outside [0, 0.9].
IsolationResult plan_isolation(const ClipperLib::Paths& copper_nm, const IsolationOptions& o);

// Islands (copper_islands()) whose tool clearances (copper grown by radius_nm) overlap: the
// narrow gaps.
std::vector<NarrowGap> find_narrow_gaps(const std::vector<Island>& islands, double radius_nm,
                                        double arc_tolerance_nm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_ISOLATION_H
