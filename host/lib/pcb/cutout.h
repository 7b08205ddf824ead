// Board cut-out: the outline (Edge.Cuts / profile) joined into closed loops, offset by the
// cutter radius to the outside of the board (into internal cut-outs), with holding tabs.
#ifndef HOST_LIB_PCB_CUTOUT_H
#define HOST_LIB_PCB_CUTOUT_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/lib/drawing/bspline.h"  // Point2
#include "host/lib/pcb/pcb_layer.h"
#include "host/lib/plan/job_defaults.h"

namespace host::pcb {

struct CutoutOptions {
  double cutter_diameter_mm = defaults::kCutterMm;
  double tab_width_mm = defaults::kTabWidthMm;  // material left standing at each tab (0: no tabs)
  int tab_count = defaults::kTabs;              // tabs on each outer loop, evenly spaced
  double tab_spacing_mm = 0;        // > 0: one tab per this much loop length instead of tab_count
  double join_tolerance_mm = 0.02;  // ends closer than this, or the stroke width, are joined
  double arc_tolerance_mm = 0.001;
};

// A stretch of the cutter path: cut at full depth, or lifted over a tab.
struct CutoutPiece {
  std::vector<Point2> points_mm;
  bool tab = false;
};

struct CutoutLoop {
  std::vector<CutoutPiece> pieces;  // in cutting order, end to start
  bool outer = true;                // around the board (false: an internal cut-out)
};

struct CutoutPlan {
  std::vector<CutoutLoop> loops;  // internal cut-outs first, the board's edge last
  int tabs = 0;
  double board_area_mm2 = 0;
  ClipperLib::Paths board_nm;      // the board as a polygon with holes (the outline's inside)
  std::vector<std::string> notes;  // strokes left out of the loops
};

// Thrown when the outline does not close into loops; what() names the file and the place.
class CutoutError : public std::runtime_error {
 public:
  explicit CutoutError(const std::string& msg) : std::runtime_error(msg) {}
};

// Closed loops from the outline's strokes as drawn: the strokes are unioned at their width
// (at least join_tolerance_mm), so duplicates, T-junctions and gaps narrower than the stroke
// merge, and the areas they enclose are the loops, along the centre lines: positive for the
// board, negative for a cut-out inside it. Strokes that enclose nothing (a stray line, a slot
// drawn inside the board) are left out with a warning added to `notes`. Throws CutoutError
// with the place where a chain stays open when nothing is enclosed.
ClipperLib::Paths outline_loops(const PcbLayer& outline, double join_tolerance_mm,
                                std::vector<std::string>* notes = nullptr);

CutoutPlan plan_cutout(const PcbLayer& outline, const CutoutOptions& options);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_CUTOUT_H
