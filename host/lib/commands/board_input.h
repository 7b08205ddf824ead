// PCB input of the engraver's commands: a single Gerber/Excellon file, a directory holding a
// board's files, or several files joined by commas ("bottom:" in front plans the bottom
// side); read into layers, planned with the board options (pcb/board_args.h), and the job's
// tool-centre paths (`points`). Errors end the command (CommandFailure) naming the file.
#ifndef HOST_LIB_COMMANDS_BOARD_INPUT_H
#define HOST_LIB_COMMANDS_BOARD_INPUT_H

#include <functional>  // std::function
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/commands/simulated_isolation.h"  // PlannedBoard
#include "host/lib/pcb/board_args.h"                // BoardArgs, BoardMachine
#include "host/lib/pcb/board_files.h"               // BoardFileSet
#include "host/lib/pcb/board_job.h"
#include "host/lib/plan/job_plan.h"

namespace host::commands {

// Where a command's notes and warnings go as they arise ("note: ...", "warning: ..."); the
// CLI prints each on stderr after "engraver: ".
using CommandLog = std::function<void(const std::string& line)>;

// A board's files as read.
struct BoardFiles {
  pcb::BoardFileSet layers;  // by kind, as the server's board jobs hold them
  std::string name;          // for output files and the job title
  std::string side;          // from a "top:" / "bottom:" prefix
  std::vector<std::string> notes;
  std::vector<std::string> warnings;  // the readers' (a parameter ignored, a tool left out)
  bool from_directory = false;        // the name is the folder's
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
// A file's or folder's name without extension (a trailing '/' left out).
std::string board_name(const std::string& input_or_file);

// Reads a board input. side_asked: --side, or "" (a "top:"/"bottom:" prefix, else the
// board's default side); in a folder only that side's copper is read.
// both_copper: the other side's copper too (a double-sided board's probe area reaches over
// the bottom side's cuts, pcb/board_probe_area.h).
BoardFiles read_board_input(const std::string& input, const std::string& side_asked = "",
                            bool both_copper = false);
// Every copper, drill and outline file of a board folder as read_board_input reads them (both
// copper sides), with its notes on which file was taken for which layer and which were left
// out; a folder without copper is not refused (`engraver info FOLDER`).
BoardFiles read_board_folder(const std::string& folder);
// One layer of a known kind (`board --top FILE` ...), its reader's warnings into `b`.
void add_named_layer(BoardFiles* b, const std::string& path, pcb::LayerKind kind);
// Every note and warning about the files into the log.
void log_board_notes(const BoardFiles& b, const CommandLog& log);

// Plans the files. measured_mm: X1 Y1 X2 Y2 of the alignment holes after the flip: the job
// is planned once without, for where they should be, then turned and shifted onto them.
pcb::BoardJob plan_board_files(const BoardFiles& b, const pcb::BoardOptions& o,
                               const std::vector<double>& measured_mm = {});
// The board options for the files; bad options end the command with the usage exit code.
pcb::BoardOptions board_options_for(const pcb::BoardArgs& args, const pcb::BoardMachine& m,
                                    const BoardFiles& b);

// Reads and plans the board for `run` and `send`: refused (exit 8) when the controller's
// points at the chord tolerance would cut copper. With `board`: the board job itself and
// what `run` checks its simulated path with.
JobPlan plan_pcb_input(const std::string& input, const pcb::BoardArgs& args,
                       const pcb::BoardMachine& m, const CommandLog& log,
                       PlannedBoard* board = nullptr);

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

// `engraver points` on PCB input: the board planned with the board options in the files'
// frame (no work area applies unless the job is placed on measured holes), and its paths.
struct BoardPoints {
  pcb::BoardJob job;
  std::vector<BoardToolPath> paths;
};
BoardPoints board_points(const std::string& input, const pcb::BoardArgs& args, double tol_mm,
                         const CommandLog& log);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_BOARD_INPUT_H
