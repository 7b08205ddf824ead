// `engraver sim` as a function: the simulated machine served on a TCP port or a serial
// device until asked to stop, with its tool path written as CSV (--trace) and a simulated
// blank for its probe (--surface).
#ifndef HOST_LIB_COMMANDS_SIM_COMMAND_H
#define HOST_LIB_COMMANDS_SIM_COMMAND_H

#include <atomic>    // std::atomic
#include <cstdint>   // uint64_t
#include <fstream>   // std::ofstream
#include <optional>  // std::optional
#include <ostream>   // std::ostream
#include <string>    // std::string

#include "host/lib/heightmap/surface_model.h"  // SurfaceSpec
#include "host/lib/sim/sim_machine.h"          // SimOptions, ToolSample
#include "host/lib/sim/sim_server.h"           // ServerOptions

namespace host::commands {

// --listen: ADDR:PORT, or serial:DEVICE (a tty or a pty's slave end; ",BAUD" is ignored), or
// a /dev path. Anything else ends the command with exit 2 (CommandFailure).
sim::ServerOptions listen_options(const std::string& listen);

// --trace: one CSV line per executed tool position (machine time, machine frame).
class TraceWriter {
 public:
  // Exit 2 (CommandFailure) when the file cannot be written.
  explicit TraceWriter(const std::string& path);
  // wall_ms: Unix time when the sample was simulated, to line up several machines' traces
  // (the machine clock may run up to the fast window ahead of it).
  void add(const sim::ToolSample& s);
  bool ok();  // flushed, and every write succeeded

 private:
  std::ofstream out_;
};

struct SimCommandOptions {
  std::string listen = "127.0.0.1:10001";
  bool realtime = false;
  std::string trace;                            // CSV file of the tool path; empty: none
  std::optional<heightmap::SurfaceSpec> blank;  // the simulated blank over the work area
  int pause_confirm_ms = sim::SimOptions{}.pause_confirm_ms;
};

struct SimCommandResult {
  uint64_t machine_ms = 0;  // machine time simulated
  int pauses_confirmed = 0;
  bool spindle_on = false;
  int spindle_switches = 0;
  bool trace_ok = true;  // false: the trace file's writes failed
};

// Serves the simulated machine until `stop` is set (a signal handler may set it), saying on
// `log` where and how. Exit 2 (CommandFailure) for a bad address or trace file.
SimCommandResult run_sim(const SimCommandOptions& o, const std::atomic<bool>& stop,
                         std::ostream& log);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_SIM_COMMAND_H
