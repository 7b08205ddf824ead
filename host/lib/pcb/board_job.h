// A whole board as one job: isolation of the copper on the chosen side, drilling with tool
// changes, and the cut-out with tabs, all layers aligned by their common file coordinates
// (mirrored for the bottom side), planned into a JobPlan checked against the work area.
#ifndef HOST_LIB_PCB_BOARD_JOB_H
#define HOST_LIB_PCB_BOARD_JOB_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/pcb/board_alignment.h"  // RigidTransform
#include "host/lib/pcb/contour_fit.h"
#include "host/lib/pcb/cutout.h"
#include "host/lib/pcb/isolation.h"
#include "host/lib/pcb/pcb_layer.h"
#include "host/lib/plan/job_plan.h"

namespace host::pcb {

enum class BoardSide { kTop, kBottom };

// The layers of one board; each optional (null: not in the job).
struct BoardLayers {
  const PcbLayer* copper_top = nullptr;
  const PcbLayer* copper_bottom = nullptr;
  const PcbLayer* drill = nullptr;
  const PcbLayer* outline = nullptr;
};

// The chord tolerance a board is sent with (#U), see job_defaults.h.
constexpr double kBoardChordToleranceMm = defaults::kBoardChordToleranceMm;

// Double-sided boards (docs/user-guide.md): both setups planned in one frame, symmetric about
// the flip axis (the vertical line through the middle of the board's outline, else of its
// holes), with alignment holes for pins drilled through the blank into the spoil board in the
// first (top) setup. The top job drills the holes and leaves the cut-out for the bottom job,
// which drills nothing (the holes go through the board).
struct AlignmentOptions {
  bool enabled = false;
  // File frame; each one is drilled with its mirror image about the flip axis. Empty: two on
  // the flip axis, below and above the board.
  std::vector<Point2> holes_file_mm;
  double hole_diameter_mm = 3.0;
  double hole_depth_mm = 3.0;  // through the blank into the spoil board
  // This setup's measured alignment (measured_alignment()): applied to every coordinate of
  // the job in the machine frame before it is encoded. Identity: none.
  RigidTransform placement;
};

struct BoardOptions {
  BoardSide side = BoardSide::kTop;  // kBottom: the bottom copper, everything mirrored in x
  IsolationOptions isolation;        // tool width, passes, overlap, mill_all
  // Cutting depth of the V-bit below the copper surface
  double isolation_depth_mm = defaults::kIsolationDepthMm;
  double fit_tolerance_mm = defaults::kBoardFitToleranceMm;  // polyline -> lines/arcs/cubics
  double z_travel_mm = defaults::kZUpMm;
  double feed_mm_per_s = defaults::kBoardFeedMmPerS;  // isolation
  double plunge_mm_per_s = defaults::kBoardPlungeMmPerS;
  // Height above the board where each plunge starts
  double drill_start_mm = defaults::kDrillStartMm;
  double drill_depth_mm = defaults::kDrillDepthMm;  // plunge depth (board thickness + breakthrough)
  double drill_feed_mm_per_s = defaults::kDrillFeedMmPerS;
  CutoutOptions cutout;
  double cutout_depth_mm = defaults::kCutDepthMm;
  double cutout_step_mm = defaults::kCutStepMm;   // depth per cut-out pass
  double tab_height_mm = defaults::kTabHeightMm;  // tabs keep this much of the board's thickness
  double cutout_feed_mm_per_s = defaults::kCutFeedMmPerS;
  bool spindle = true;  // spindle on/off steps and spin-up dwells
  uint32_t spindle_spinup_ms = defaults::kSpindleSpinupMs;
  // The job's lower-left corner (tool extent) in the machine
  double margin_mm = defaults::kBoardMarginMm;
  double work_width_mm = defaults::work_width_mm();
  double work_height_mm = defaults::work_height_mm();
  // The controller's travel: the work area may not be larger (check_work_area()).
  double travel_width_mm = defaults::travel_mm(config::kAxisX);
  double travel_height_mm = defaults::travel_mm(config::kAxisY);
  bool allow_narrow_gaps = false;  // plan anyway (the gaps stay in the report)
  AlignmentOptions alignment;
};

// How file coordinates (mm) map into the machine frame: x' = sx * x + offset.x, y' = y + offset.y,
// then the measured placement of a double-sided board's second setup.
struct BoardFrame {
  double sx = 1.0;  // -1 for the bottom side
  Point2 offset_mm{0, 0};
  RigidTransform placement;
  Point2 to_machine(const Point2& file_mm) const {
    return placement.apply(Point2(sx * file_mm.x() + offset_mm.x(), file_mm.y() + offset_mm.y()));
  }
  ClipperLib::Paths to_machine_nm(const ClipperLib::Paths& file_nm) const;
  Point2 to_file(const Point2& machine_mm) const {
    const Point2 m = placement.inverse().apply(machine_mm);
    return Point2((m.x() - offset_mm.x()) / sx, m.y() - offset_mm.y());
  }
};

struct BoardReport {
  size_t islands = 0;
  std::vector<NarrowGap> narrow_gaps;  // places in the file frame
  size_t isolation_contours = 0;
  double isolation_length_mm = 0;
  size_t isolation_vertices = 0;  // of the flattened contours (the G1 lines they would be)
  FitStats fit;
  size_t holes = 0;        // what this job drills (alignment holes too; a bottom side after a top
                           // side with alignment holes: none, the top side drilled them all)
  size_t board_holes = 0;  // the drill files' holes, drilled by this job or not
  size_t holes_on_copper = 0;  // of board_holes, centre inside this side's copper: the layers
                               // line up
  size_t slots = 0;
  size_t drill_tools = 0;
  double drill_travel_file_order_mm = 0;
  double drill_travel_ordered_mm = 0;
  int tabs = 0;
  double cutout_length_mm = 0;
  std::string no_cutout;    // why the job cuts no board out ("no outline layer"); "": it does
  size_t tool_changes = 0;  // kPause steps
  std::string first_tool;   // mounted before the job starts
  std::vector<std::string> notes;  // what the planner left out and why (an empty outline)
};

// A tool of the job, in the order they are mounted (tools[0] before the job starts).
struct BoardTool {
  std::string label;  // as on the LCD at its change ("Drill 0.80mm")
  double diameter_mm = 0;
};

struct BoardJob {
  JobPlan plan;
  std::vector<BoardTool> tools;
  BoardReport report;
  BoardFrame frame;
  size_t isolation_curves = 0;  // plan.curves[0 .. isolation_curves) isolate copper
  double tool_radius_mm = 0;    // isolation tool
  // The isolated copper in the machine frame, in islands (worked out once: the plot and
  // every check of `board` and `run` take them).
  std::vector<Island> copper_machine;
  ClipperLib::Paths board_machine_nm;  // the board inside its outline, machine frame
  std::vector<std::vector<Point2>> isolation_paths_mm;  // planned tool centres, machine frame
  std::vector<Hole> holes_machine;                      // nm, machine frame
  std::vector<Slot> slots_machine;
  std::vector<std::vector<Point2>> cutout_paths_mm;  // machine frame
  std::vector<std::vector<Point2>> tab_paths_mm;     // stretches lifted over tabs
  double cutter_radius_mm = 0;
  // The clearing tool's curves follow the isolation's: plan.curves[isolation_curves ..
  // isolation_curves + clearing_curves).
  size_t clearing_curves = 0;
  double clearing_tool_radius_mm = 0;
  std::vector<std::vector<Point2>> clearing_paths_mm;  // its planned tool centres, machine frame
  // Double-sided: the alignment holes (hole 1 first) where the pins stand, machine frame
  // before this setup's placement; and the flip axis (file frame, x).
  std::vector<Point2> alignment_holes_mm;
  double flip_axis_file_x_mm = 0;
};

// Text of a narrow gap for messages: "gap 0.120 mm < tool 0.200 mm at (x, y) mm"; the gap
// and what the tool needs with as many digits as it takes for them to differ ("gap 0.0571
// mm < tool 0.0572 mm", never "0.057 < 0.057").
std::string describe_gap(const NarrowGap& g, const IsolationOptions& o);
// A length as an option took it, in mm: 3 decimals, more when it has them (to the
// nanometre): 0.2 -> "0.200", 0.0415 -> "0.0415".
std::string mm_text(double mm);

// Plans the board. Throws PlanError (narrow gaps unless allowed, nothing to do, the work
// area, a curve the firmware cannot hold) and CutoutError (an outline that does not close).
BoardJob plan_board(const BoardLayers& layers, const BoardOptions& options);

// Name of a drill or cutter size for the LCD (at most 16 characters): "Drill 0.80mm".
std::string tool_label(const char* what, double diameter_mm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_BOARD_JOB_H
