// Exit codes of the `engraver` tool and the exception a command (a host/lib/commands function
// or the CLI binding it) throws to end with one.
#ifndef HOST_LIB_COMMANDS_EXIT_CODES_H
#define HOST_LIB_COMMANDS_EXIT_CODES_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string

namespace host::commands {

// Every exit code of the tool, documented in docs/user-guide.md ("Exit codes"); the --help
// footer lists them from kExitCodes below.
enum ExitCode {
  kExitOk = 0,         // done
  kExitJobFailed = 1,  // the job was refused or failed (plan, work area, validation, link)
  kExitUsage = 2,      // bad command line or unreadable / invalid input file
  kExitAborted = 3,    // send/run: the job was aborted (x, Ctrl-C, SIGTERM)
  kExitAlarm = 4,      // send/run: the machine raised an alarm
  kExitRefused = 5,    // send/run/probe: the controller refused a command (a stopped touch too)
  kExitLinkLost = 6,   // send/run: the link failed
  kExitStalled = 7,    // send/run: no progress for 30 s
  // The job's tool paths (planned, or simulated by `run`) would cut copper: refused.
  kExitCutsCopper = 8,
  kExitInternal = 70  // an unexpected failure inside the tool (a bug); sysexits' EX_SOFTWARE
};

// The codes and what they mean in a few words, for --help.
struct ExitCodeText {
  int code;
  const char* text;
};
inline constexpr ExitCodeText kExitCodes[] = {
    {kExitOk, "done"},
    {kExitJobFailed, "job refused or failed"},
    {kExitUsage, "usage or input error"},
    {kExitAborted, "send/run: job aborted (x, Ctrl-C, SIGTERM)"},
    {kExitAlarm, "send/run: machine alarm"},
    {kExitRefused,
     "send/run/probe: command refused by the controller, or a probe touch stopped by Ctrl-C"},
    {kExitLinkLost, "send/run/probe: link lost"},
    {kExitStalled, "send/run: stalled (no progress for 30 s)"},
    {kExitCutsCopper, "board/run/send: the tool would cut copper"},
    {kExitInternal, "internal error"}};

// "0 done; 1 job refused or failed; ...; 70 internal error".
inline std::string exit_codes_summary() {
  std::string s;
  for (const ExitCodeText& e : kExitCodes) {
    if (!s.empty()) s += "; ";
    s += std::to_string(e.code) + " " + e.text;
  }
  return s;
}

// Thrown by a command to print what() on stderr and exit with code.
class CommandFailure : public std::runtime_error {
 public:
  CommandFailure(int exit_code, const std::string& msg)
      : std::runtime_error(msg), code(exit_code) {}
  int code;
};

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_EXIT_CODES_H
