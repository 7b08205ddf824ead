// Exit codes of the `engraver` tool and the exception a command throws to end with one.
#ifndef HOST_CLI_EXIT_CODES_H
#define HOST_CLI_EXIT_CODES_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string

namespace host::cli {

// Documented in docs/user-guide.md ("Exit codes"); groups may add codes from 3 upwards
// (below 70).
enum ExitCode {
  kExitOk = 0,         // done
  kExitJobFailed = 1,  // the job was refused or failed (plan, work area, validation, link)
  kExitUsage = 2,      // bad command line or unreadable / invalid input file
  // The job's tool paths (planned, or simulated by `run`) would cut copper: refused.
  // 3..7 are send/run's (machine_commands.cpp).
  kExitCutsCopper = 8,
  kExitInternal = 70  // an unexpected failure inside the tool (a bug); sysexits' EX_SOFTWARE
};

// Thrown by a command to print what() on stderr and exit with code.
class CommandFailure : public std::runtime_error {
 public:
  CommandFailure(int exit_code, const std::string& msg)
      : std::runtime_error(msg), code(exit_code) {}
  int code;
};

}  // namespace host::cli

#endif  // HOST_CLI_EXIT_CODES_H
