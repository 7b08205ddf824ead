// PCB boards on the command line: `engraver board` (plan, check, plot and report a whole
// board) and the hooks through which `points`, `run` and `send` take PCB files: a single
// Gerber/Excellon file, a directory holding a board's files, or several files joined by
// commas ("bottom:" in front plans the bottom side).
#ifndef HOST_CLI_BOARD_CLI_H
#define HOST_CLI_BOARD_CLI_H

#include <CLI/CLI.hpp>  // CLI::App

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/commands/board_input.h"  // PlannedBoard, CommandLog, is_pcb_input
#include "host/lib/pcb/board_args.h"        // BoardArgs, BoardMachine
#include "host/lib/plan/job_defaults.h"
#include "host/lib/plan/job_plan.h"

namespace host::cli {

// Board options shared by `board`, `run` and `send` (tools, passes, depths, tabs, side), and
// the machine a board is planned for (host/lib/pcb/board_args.h: the server's too).
using BoardArgs = pcb::BoardArgs;
using MachineDefaults = pcb::BoardMachine;

// Adds the board options to a command, in their own group (kBoardOptionsGroup).
inline constexpr const char* kBoardOptionsGroup = "PCB boards";
void add_board_options(CLI::App* cmd, BoardArgs* args);

// Board options that cannot go together, refused as the line is read (a usage error, exit 2)
// rather than after the files' notes.
void refuse_board_option_combinations(const BoardArgs& args);

using commands::input_exists;
using commands::input_name;
using commands::is_pcb_input;

// Notes and warnings of the board commands on stderr ("engraver: note: ...").
commands::CommandLog stderr_log();

// Reads and plans the board; errors end the command (CommandFailure) naming the file. With
// `board`: the board job itself and what `run` checks its simulated path with.
JobPlan plan_pcb_input(const std::string& input, const BoardArgs& args, const MachineDefaults& d,
                       commands::PlannedBoard* board = nullptr);

// `engraver points` on PCB input, planned with the board options: every tool-centre path of
// the job, tool by tool (the controller's points at tol_mm for curves), in the files' frame.
// False when the input is not PCB files.
bool print_board_points_if_pcb(const std::string& input, const BoardArgs& args, double tol_mm,
                               bool csv);

}  // namespace host::cli

#endif  // HOST_CLI_BOARD_CLI_H
