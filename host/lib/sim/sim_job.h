// A job through the simulated machine in one process: the sender streams the plan to the
// simulated machine (in lockstep, or over loopback TCP), and the tool path is measured as it
// is made.
#ifndef HOST_LIB_SIM_SIM_JOB_H
#define HOST_LIB_SIM_SIM_JOB_H

#include <functional>  // std::function
#include <memory>      // std::unique_ptr
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/plan/job_plan.h"
#include "host/lib/plan/pen_path.h"
#include "host/lib/sim/sim_machine.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"

namespace host::sim {

struct SimJobOptions {
  SimOptions machine;
  EncodeOptions encode;
  SenderOptions sender;  // its clock is set here: machine time in lockstep, else the wall
  bool realtime = false;
  // false: sender and machine in one thread, in lockstep (SimLink); machine time runs as fast
  // as the CPU allows and the run is the same every time. true: the machine serves a
  // loopback TCP port from a thread (SimServer), as `engraver sim` does.
  bool over_tcp = false;
  // What the result keeps of the tool path: every sample (0: SimJobResult::trace) or a
  // plot's path thinned to this step in mm (SimJobResult::plot_path). The measurements
  // always use every sample.
  double trace_step_mm = 0.0;
  // With a step: the plot path keeps at most about this many positions (8 bytes each); a
  // longer job's gets a coarser step (SimJobResult::trace_step_mm) instead of more memory.
  size_t trace_max_samples = size_t{1} << 20;
  // Wraps the sender's link (tests put a noisy or dropping link here).
  std::function<std::unique_ptr<Link>(std::unique_ptr<Link>)> wrap_link;
  // Sees every tool sample as it is made (e.g. to check the cut path at full resolution).
  std::function<void(const ToolSample&)> on_sample;
  // Called at every status (e.g. to hold/resume/abort through the sender).
  std::function<void(Sender&, const Progress&)> on_progress;
  // Called once the session is open, before the job: may use the sender (e.g. to probe the
  // blank) and returns commands sent just before the job's (e.g. the height map); they are
  // not counted in the job's commands or wire bytes. A throw ends the run (passed on).
  std::function<std::vector<QueuedCommand>(Sender&)> before_job;
  // Called with the link once the stream has ended, however it ended (a throw from before_job
  // too, before it passes on), with the sender's options (its clock): e.g. to raise the tool
  // after an operator's abort. Must not throw.
  std::function<void(Link&, const SenderOptions&)> after_stream;
  // The height (mm) the controller adds to the planned Z at (x, y) (a height map it follows),
  // taken off the samples the job is measured and plotted by (pen up/down, path lengths), so
  // they are classified by their planned heights. Empty: none.
  std::function<double(double x_mm, double y_mm)> z_offset_mm;
};

// Commands sent just before the job (a height map, or its clearing): not the job's own.
struct SetupSent {
  size_t commands = 0;
  size_t wire_bytes = 0;
};

struct SimJobResult {
  JobOutcome outcome = JobOutcome::kLinkLost;
  std::string message;
  SenderStats stats;
  size_t commands = 0;
  size_t executed = 0;                // commands whose execution finished, set-up ones included
  size_t commands_held_max = 0;       // the most encoded commands held at once (streamed: a window)
  size_t wire_bytes = 0;              // the job's frames once each (no retransmits, no polls)
  uint16_t job_id = 0;                // job_id_of() the commands: the job's identity (#J)
  SetupSent setup;                    // sent before the job (SimJobOptions::before_job)
  uint64_t virtual_ms = 0;            // machine time simulated
  double wall_s = 0;                  // real time it took
  double cpu_s = 0;                   // processor time this thread used for it (load-independent)
  std::vector<ToolSample> trace;      // every tool position (machine frame, mm); step 0 only
  PenPath plot_path;                  // the path thinned for a plot (machine frame); a step only
  size_t trace_samples = 0;           // samples measured (before thinning)
  double trace_step_mm = 0;           // step the plot path was thinned to at the end
  double motion_s = 0;                // from the first to the last tool movement
  double cut_s = 0;                   // pen down and moving in X/Y
  double cut_mm = 0, rapid_mm = 0;    // tool path lengths from the trace (pen down / up)
  double max_contour_error_um = 0;    // pen-down trace points to the planned curves
  ToolSample worst_contour_sample{};  // where that error is largest
  std::string lcd[2];
  int pauses_confirmed = 0;  // #P pauses the simulated operator confirmed
  bool spindle_on = false;   // at the end of the run
};

// Runs the plan on a fresh simulated machine. Throws PlanError/LinkError for what cannot
// start at all; every other ending is in the result.
SimJobResult run_sim_job(const JobPlan& plan, const SimJobOptions& options);

// Pen-down samples: Z below halfway between the plan's highest cutting height (pen down into
// the work, drill bottoms) and its lowest travel height above that (pen up, drill start).
double pen_threshold_mm(const JobPlan& plan);

}  // namespace host::sim

#endif  // HOST_LIB_SIM_SIM_JOB_H
