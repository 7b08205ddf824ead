// Entry point of the `engraver` tool: the command line, the registered command groups and
// the mapping of failures to documented exit codes.
#include <CLI/CLI.hpp>  // CLI::App

#include <iostream>  // std::cerr

#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_plan.h"

#ifndef ENGRAVER_VERSION
#define ENGRAVER_VERSION "unknown"
#endif

// Only setup before the try can throw outside it (CLI11 rejecting a duplicate option: a bug
// in this program); std::terminate's report is the right outcome for that.
// NOLINTNEXTLINE(bugprone-exception-escape)
int main(int argc, char** argv) {
  CLI::App app{
      "engraver: engrave DXF drawings on the PCB engraving machine (plan, simulate, send).",
      "engraver"};
  app.footer(
      "Examples:\n"
      "  engraver info samples/engraver-word.dxf\n"
      "  engraver points samples/engraver-word.dxf --tol 0.005 --csv > points.csv\n"
      "\nExit codes: 0 done; 1 job refused or failed; 2 usage or input error; send and run "
      "also 3 aborted, 4 machine alarm, 5 command refused by the controller, 6 link lost "
      "(docs/user-guide.md, \"Exit codes\"). Each command's --help lists its own.");
  app.set_version_flag("--version", std::string("engraver ") + ENGRAVER_VERSION);
  app.require_subcommand(1);
  host::cli::add_registered_commands(app);
  const std::string unknown = host::cli::unknown_command_message(app, argc, argv);
  if (!unknown.empty()) {
    std::cerr << "engraver: " << unknown << "\n";
    return host::cli::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and the usage hint
    return host::cli::kExitUsage;
  } catch (const host::cli::CommandFailure& e) {
    std::cerr << "engraver: " << e.what() << "\n";
    return e.code;
  } catch (const host::ImportError& e) {
    std::cerr << "engraver: " << e.what() << "\n";
    return host::cli::kExitUsage;
  } catch (const host::PlanError& e) {
    std::cerr << "engraver: job refused: " << e.what() << "\n";
    return host::cli::kExitJobFailed;
  } catch (const std::exception& e) {
    std::cerr << "engraver: " << e.what() << "\n";
    return host::cli::kExitJobFailed;
  }
  return host::cli::kExitOk;
}
