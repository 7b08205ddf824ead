// PCB boards on the command line: `engraver board` (plan, check, plot and report a whole
// board) and the hooks through which `points`, `run` and `send` take PCB files: a single
// Gerber/Excellon file, a directory holding a board's files, or several files joined by
// commas ("bottom:" in front plans the bottom side).
#ifndef HOST_CLI_BOARD_CLI_H
#define HOST_CLI_BOARD_CLI_H

#include <CLI/CLI.hpp>  // CLI::App

#include <memory>    // std::shared_ptr
#include <optional>  // std::optional
#include <string>    // std::string
#include <vector>    // std::vector

#include "host/lib/commands/simulated_isolation.h"  // PlannedBoard
#include "host/lib/pcb/board_job.h"
#include "host/lib/pcb/isolation_check.h"  // IsolationCheck
#include "host/lib/plan/job_defaults.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/plot/plot.h"  // ToolPathSegment

namespace host::cli {

// Board options shared by `board`, `run` and `send` (tools, passes, depths, tabs, side).
struct BoardArgs {
  double tool_width_mm = defaults::kToolWidthMm;
  int passes = defaults::kPasses;
  double overlap = defaults::kOverlap;
  double clearance_mm = defaults::kClearanceMm;
  bool mill_all = false;
  bool isolate_empty_holes = false;  // hatched pours' openings (IsolationOptions)
  double depth_mm = defaults::kIsolationDepthMm;
  double drill_depth_mm = defaults::kDrillDepthMm;
  double drill_start_mm = defaults::kDrillStartMm;
  double drill_feed_mm_s = defaults::kDrillFeedMmPerS;
  double cutter_mm = defaults::kCutterMm;
  double cut_depth_mm = defaults::kCutDepthMm;
  double cut_step_mm = defaults::kCutStepMm;
  double cut_feed_mm_s = defaults::kCutFeedMmPerS;
  double tab_width_mm = defaults::kTabWidthMm;
  int tabs = defaults::kTabs;
  double tab_spacing_mm = 0;  // > 0: one tab per this much outline instead of --tabs
  double tab_height_mm = defaults::kTabHeightMm;
  bool no_spindle = false;
  bool allow_narrow_gaps = false;
  std::string side;             // "top", "bottom" or empty (the side whose copper is given)
  double clearing_tool_mm = 0;  // > 0: a wider tool for the outer passes
  int narrow_passes = 1;        // with a clearing tool: passes of the isolation tool
  // Double-sided: "auto" or "X,Y[;X,Y...]" (file frame, mm); empty: no alignment holes.
  std::string align_holes;
  double align_diameter_mm = 3.0;
  double align_depth_mm = 3.0;
  std::vector<double> align_measured_mm;  // X1 Y1 X2 Y2: holes 1 and 2 measured after the flip
};

// Adds the board options to a command, in their own group (kBoardOptionsGroup).
inline constexpr const char* kBoardOptionsGroup = "PCB boards";
void add_board_options(CLI::App* cmd, BoardArgs* args);

// The machine options `engraver board` plans with, which `run` and `send` also take for PCB
// files where none is given.
struct MachineDefaults {
  double feed_mm_s = defaults::kBoardFeedMmPerS;
  double chord_tol_mm = defaults::kBoardChordToleranceMm;  // of the controller's points (#U)
  double z_up_mm = defaults::kZUpMm;
  double margin_mm = defaults::kBoardMarginMm;
  double work_w_mm = defaults::work_width_mm(), work_h_mm = defaults::work_height_mm();
};

// True when `input` names PCB files (a Gerber/Excellon file, a directory with some, a
// comma-separated list, optionally "bottom:"/"top:" in front).
bool is_pcb_input(const std::string& input);
// True when every file `input` names (the same forms) exists, or it names a directory.
bool input_exists(const std::string& input);

// The name outputs are called by: a directory's own name (also with a trailing '/'), else
// the first file's stem; a "top:"/"bottom:" prefix and further comma-separated files are
// left out. For drawings too.
std::string input_name(const std::string& input);

// Reads and plans the board; errors end the command (CommandFailure) naming the file. With
// `board`: the board job itself and what `run` checks its simulated path with.
JobPlan plan_pcb_input(const std::string& input, const BoardArgs& args, const MachineDefaults& d,
                       commands::PlannedBoard* board = nullptr);

// `engraver points` on PCB input, planned with the board options: every tool-centre path of
// the job, tool by tool (the controller's points at tol_mm for curves), in the files' frame.
// False when the input is not PCB files.
bool print_board_points_if_pcb(const std::string& input, const BoardArgs& args, double tol_mm,
                               bool csv);

// One run of tool-centre points traced at one depth with one tool.
struct BoardToolPath {
  size_t tool = 0;                     // index into BoardJob::tools
  size_t path = 0;                     // index in the job's order
  int32_t z_um = 0;                    // machine Z (below the surface: negative)
  std::vector<Point2> points_file_mm;  // the files' frame
};
// The job's paths: isolation contours, drill holes (one point each, at the drill's depth),
// slots and cut-out passes (a new path at each change of depth, as over a tab), with the
// controller's points at the chord tolerance for curves.
std::vector<BoardToolPath> board_tool_paths(const pcb::BoardJob& job, int chord_tolerance_um);

}  // namespace host::cli

#endif  // HOST_CLI_BOARD_CLI_H
