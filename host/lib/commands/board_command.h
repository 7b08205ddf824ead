// `engraver board` as a function: a whole board's files read, planned, checked, plotted and
// reported, in stages (plan, check, report, write) the CLI and the tests call.
#ifndef HOST_LIB_COMMANDS_BOARD_COMMAND_H
#define HOST_LIB_COMMANDS_BOARD_COMMAND_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <optional>  // std::optional
#include <string>    // std::string
#include <vector>    // std::vector

#include "host/lib/commands/board_input.h"  // BoardFiles, CommandLog
#include "host/lib/pcb/board_args.h"
#include "host/lib/pcb/board_job.h"
#include "host/lib/pcb/isolation_check.h"  // IsolationCheck
#include "host/lib/plan/job_defaults.h"

namespace host::commands {

struct BoardCommandOptions {
  std::vector<std::string> files;    // files, folders, "top:"/"bottom:" lists (board_input.h)
  std::string top, bottom, outline;  // layers named by their kind
  std::vector<std::string> drills;
  pcb::BoardArgs board;
  pcb::BoardMachine machine;
  double tol_mm = defaults::kChordToleranceMm;  // of the G1 comparison (wire_bytes)
  std::string outdir = "out";                   // NAME.board.svg/.json (and .png)
  bool check = true;                            // the geometric isolation check
  bool plot = true;
  bool png = false;  // the plot as NAME.board.png too (--png): most of a small board's time
  // The isolation encoded three more ways (compact, fixed-width frames, G1 lines) to compare
  // bytes for docs/performance.md; off, the report has no such fields.
  bool wire_bytes = false;
};

// The isolation's bytes as sent and as other encodings would send it (wire_bytes).
struct WireMeasure {
  size_t spline_frames = 0;
  size_t spline_bytes = 0;          // #B and #Q (or #K) frames of the isolation (as sent)
  size_t spline_bytes_compact = 0;  // the same with #K frames only (protocol 2)
  size_t spline_bytes_full = 0;     // the same with #D frames (fixed-width fields)
  size_t g1_lines = 0;              // the same curves as G1 lines at the chord tolerance
  size_t g1_bytes = 0;
  size_t g1_vertex_bytes = 0;  // G1 through every vertex of Clipper's flattened contours
};
WireMeasure measure_wire(const pcb::BoardJob& job, double tol_mm);

// Bytes of the job's frames as sent (set-up frames left out), tool by tool in job order.
std::vector<size_t> bytes_per_tool(const pcb::BoardJob& job);

struct BoardResult {
  std::string name;  // the board's (output files, title)
  pcb::BoardOptions options;
  pcb::BoardJob job;
  double plan_cpu_s = 0, plan_wall_s = 0, plan_peak_mb = 0;  // files -> plan
  std::optional<WireMeasure> wire;
  std::vector<size_t> tool_bytes;
  std::optional<pcb::IsolationCheck> check;  // when checked and the board has copper
  bool check_ok = true;                      // no hits, no more joined pairs than narrow gaps
  std::string base;                          // OUTDIR/NAME
};

// Stage 1: the files read (notes into the log) and planned; bad input ends the command
// (CommandFailure: 2 unreadable or bad options, 1 refused by the planner).
BoardFiles read_board_command_files(const BoardCommandOptions& o, const CommandLog& log);
BoardResult plan_board_command(const BoardCommandOptions& o, const CommandLog& log);
// Stage 2: the planned isolation checked against the copper (o.check), the bytes measured.
void check_board(const BoardCommandOptions& o, BoardResult* r, const CommandLog& log);
// A plan's narrow gaps for a report (`board`'s and `run`'s): each place (in the files'
// frame), width and pair of islands.
nlohmann::json narrow_gaps_json(const std::vector<pcb::NarrowGap>& gaps);
// Stage 3: the report as JSON and as the lines `board` prints.
nlohmann::json board_report_json(const BoardCommandOptions& o, const BoardResult& r);
std::string board_report_text(const BoardCommandOptions& o, const BoardResult& r);
// Stage 4: OUTDIR/NAME.board.json and (o.plot) .svg, (o.png) .png; sets r->base.
void write_board_outputs(const BoardCommandOptions& o, const nlohmann::json& report,
                         BoardResult* r);
// Stage 5: ends the command when the planned paths cut copper (exit 8) or the check failed
// (exit 1).
void refuse_failed_board(const BoardResult& r);

// Stages 1 and 2.
BoardResult run_board(const BoardCommandOptions& o, const CommandLog& log);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_BOARD_COMMAND_H
