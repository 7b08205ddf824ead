// Entry point of the `engraver` tool: the command line, the registered command groups, and
// the guard that maps every failure to a message and a documented exit code.
#include <CLI/CLI.hpp>  // CLI::App

#include <cstring>   // std::strcmp
#include <iostream>  // std::cerr

#include "host/cli/command_guard.h"
#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"

#ifndef ENGRAVER_VERSION
#define ENGRAVER_VERSION "unknown"
#endif

// Setup before the guard can only throw for a bug in this program (CLI11 rejecting a
// duplicate option); std::terminate's report is the right outcome for that.
// NOLINTNEXTLINE(bugprone-exception-escape)
int main(int argc, char** argv) {
  CLI::App app{
      "engraver: engrave DXF drawings on the PCB engraving machine (plan, simulate, send).",
      "engraver"};
  app.footer(
      "Examples:\n"
      "  engraver info samples/engraver-word.dxf\n"
      "  engraver points samples/engraver-word.dxf --tol 0.005 --csv > points.csv\n"
      "\nExit codes: " +
      host::cli::exit_codes_summary() +
      " (docs/user-guide.md, \"Exit codes\"). Each command's --help lists its own.");
  app.set_version_flag("--version", std::string("engraver ") + ENGRAVER_VERSION);
  app.require_subcommand(1);
  host::cli::add_registered_commands(app, argc, argv);
  const std::string unknown = host::cli::unknown_command_message(app, argc, argv);
  if (!unknown.empty()) {
    std::cerr << "engraver: " << unknown << "\n";
    return host::cli::kExitUsage;
  }
  host::cli::install_terminate_guard(app);
  // `engraver -h serve` as `engraver serve --help`: serve's options are engraver-serve's, so
  // the forwarder's own help has none.
  const char* serve_help[] = {argv[0], "serve", "--help"};
  if (argc == 3 && (std::strcmp(argv[1], "-h") == 0 || std::strcmp(argv[1], "--help") == 0) &&
      std::strcmp(argv[2], "serve") == 0)
    return host::cli::run_guarded(app, 3, serve_help, std::cerr);
  return host::cli::run_guarded(app, argc, argv, std::cerr);
}
