// The board options a person chooses (the command line's --tool-width ... --align-measured,
// the server's board settings) and the one resolver that turns them into the planner's
// BoardOptions for a set of layers: `engraver board`, `points`, `run`, `send` and the
// server's board jobs all plan through resolve_board_options().
#ifndef HOST_LIB_PCB_BOARD_ARGS_H
#define HOST_LIB_PCB_BOARD_ARGS_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/lib/pcb/board_files.h"  // BoardFileSet
#include "host/lib/pcb/board_job.h"    // BoardOptions
#include "host/lib/plan/job_defaults.h"

namespace host::pcb {

// The isolation tool, its passes and depth (--tool-width ... --depth).
struct BoardIsolationArgs {
  double tool_width_mm = defaults::kToolWidthMm;
  int passes = defaults::kPasses;
  double overlap = defaults::kOverlap;
  double clearance_mm = defaults::kClearanceMm;
  bool mill_all = false;
  bool isolate_empty_holes = false;  // hatched pours' openings (IsolationOptions)
  double clearing_tool_mm = 0;       // > 0: a wider tool for the outer passes
  int narrow_passes = 1;             // with a clearing tool: passes of the isolation tool
  double depth_mm = defaults::kIsolationDepthMm;
};

// Drilling (--drill-depth, --drill-start, --drill-feed).
struct BoardDrillArgs {
  double depth_mm = defaults::kDrillDepthMm;
  double start_mm = defaults::kDrillStartMm;
  double feed_mm_s = defaults::kDrillFeedMmPerS;
};

// The cut-out and its holding tabs (--cutter ... --tab-height).
struct BoardCutoutArgs {
  double cutter_mm = defaults::kCutterMm;
  double depth_mm = defaults::kCutDepthMm;
  double step_mm = defaults::kCutStepMm;
  double feed_mm_s = defaults::kCutFeedMmPerS;
  double tab_width_mm = defaults::kTabWidthMm;
  int tabs = defaults::kTabs;
  double tab_spacing_mm = 0;  // > 0: one tab per this much outline instead of --tabs
  double tab_height_mm = defaults::kTabHeightMm;
};

// A double-sided board's alignment holes (--align-holes ... --align-measured).
struct BoardAlignmentArgs {
  // "auto" or "X,Y[;X,Y...]" (file frame, mm); empty: no alignment holes.
  std::string holes;
  double diameter_mm = defaults::kAlignDiameterMm;
  double depth_mm = defaults::kAlignDepthMm;
  std::vector<double> measured_mm;  // X1 Y1 X2 Y2: holes 1 and 2 measured after the flip
};

// Board options (tools, passes, depths, tabs, side), as the command line names them, in the
// command line's groups.
struct BoardArgs {
  BoardIsolationArgs isolation;
  BoardDrillArgs drill;
  BoardCutoutArgs cutout;
  BoardAlignmentArgs alignment;
  std::string side;  // "top", "bottom" or empty (the side whose copper is given)
  bool no_spindle = false;
  bool allow_narrow_gaps = false;
};

// The machine a board is planned for: what `engraver board` plans with, and what `run` and
// `send` take for PCB files where none is given.
struct BoardMachine {
  double feed_mm_s = defaults::kBoardFeedMmPerS;
  double chord_tol_mm = defaults::kBoardChordToleranceMm;  // of the controller's points (#U)
  double z_up_mm = defaults::kZUpMm;
  double margin_mm = defaults::kBoardMarginMm;
  double work_w_mm = defaults::work_width_mm(), work_h_mm = defaults::work_height_mm();
};

// Options that cannot plan a job, in the command line's words (--side, --clearing-tool ...):
// the CLI ends with the usage exit code, the server names its fields instead.
class BoardArgsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Options each within its range (option_ranges in the CLI) that cannot go together: throws
// BoardArgsError naming them. resolve_board_options asks it too; the CLI asks it first, as
// the line is read, before any file is.
void refuse_option_combinations(const BoardArgs& a);

// "top" or "bottom": the words for a side, everywhere a side is asked for.
bool is_board_side(const std::string& side);
// The side whose copper is given: "bottom" when only bottom copper is, else "top".
std::string side_of_copper(const BoardFileSet& layers);

// The side the job is planned for: `asked` (--side), else `prefix` (a "top:"/"bottom:"
// input), else the copper given (bottom when only bottom copper is there). Throws
// BoardArgsError for another word.
BoardSide resolve_board_side(const std::string& asked, const std::string& prefix,
                             const BoardFileSet& layers);

// "auto" (empty holes_file_mm) or "X,Y[;X,Y...]" (mm, files' frame) into holes_file_mm;
// "" when fine, else why not (naming --align-holes).
std::string parse_align_holes(const std::string& text, std::vector<Point2>* holes_file_mm);

// The planner's options for these layers. prefix_side: the input's "top:"/"bottom:" prefix.
// Throws BoardArgsError for copper of the other side only, a clearing tool without passes
// for it, --narrow-passes without a clearing tool, unreadable --align-holes, or
// --align-measured without alignment holes.
BoardOptions resolve_board_options(const BoardArgs& args, const BoardMachine& machine,
                                   const BoardFileSet& layers, const std::string& prefix_side);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_BOARD_ARGS_H
