// The whole-process guard of the `engraver` tool: parses the command line, runs the chosen
// command, and turns every exception that escapes it into one line on stderr naming the
// command and its file, and a documented exit code (exit_codes.h, docs/user-guide.md).
#ifndef HOST_CLI_COMMAND_GUARD_H
#define HOST_CLI_COMMAND_GUARD_H

#include <CLI/CLI.hpp>  // CLI::App

#include <ostream>  // std::ostream
#include <string>   // std::string

namespace host::cli {

// "info samples/engraver-word.dxf": the subcommands the user chose and their positional
// arguments (the files); "" before parsing.
std::string describe_command(const CLI::App& app);

// Parses argv into app and runs the command; returns the exit code. Messages go to err.
int run_guarded(CLI::App& app, int argc, const char* const* argv, std::ostream& err);

// From here on, an exception that escapes a thread (std::terminate) prints the command that
// was running and ends the process with kExitInternal instead of a bare abort.
void install_terminate_guard(CLI::App& app);

}  // namespace host::cli

#endif  // HOST_CLI_COMMAND_GUARD_H
