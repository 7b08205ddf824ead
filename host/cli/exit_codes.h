// The CLI's names for the tool's exit codes, declared once in host/lib/commands/exit_codes.h.
#ifndef HOST_CLI_EXIT_CODES_H
#define HOST_CLI_EXIT_CODES_H

#include "host/lib/commands/exit_codes.h"

namespace host::cli {

using commands::CommandFailure;
using commands::exit_codes_summary;
using commands::ExitCode;
using commands::ExitCodeText;
using commands::kExitAborted;
using commands::kExitAlarm;
using commands::kExitCodes;
using commands::kExitCutsCopper;
using commands::kExitInternal;
using commands::kExitJobFailed;
using commands::kExitLinkLost;
using commands::kExitOk;
using commands::kExitRefused;
using commands::kExitStalled;
using commands::kExitUsage;

}  // namespace host::cli

#endif  // HOST_CLI_EXIT_CODES_H
