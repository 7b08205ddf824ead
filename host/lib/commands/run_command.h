// `engraver run` as a function: a planned job sent to a simulated machine in the same process,
// in stages (simulate, plot, check, report), each a function the CLI and the tests call.
#ifndef HOST_LIB_COMMANDS_RUN_COMMAND_H
#define HOST_LIB_COMMANDS_RUN_COMMAND_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <functional>  // std::function
#include <memory>      // std::shared_ptr
#include <optional>    // std::optional
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/commands/simulated_isolation.h"  // PlannedBoard, SimulatedIsolation
#include "host/lib/heightmap/depth_meter.h"         // DepthOptions, DepthReport
#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"  // SurfaceSpec
#include "host/lib/plan/job_defaults.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/sim/cut_paths.h"
#include "host/lib/sim/sim_job.h"
#include "host/lib/stream/job_encoder.h"  // EncodeOptions

namespace host::commands {

// A double-sided board's second setup, simulated (run --blank-error): the blank on the pins
// off by an error, the simulated operator measuring the alignment holes (unless pins only),
// the job aligned to them.
struct FlipSimulation {
  double dx_mm = 0, dy_mm = 0, rotation_deg = 0;  // the blank's placement error as given
  bool pins_only = false;                         // no measured alignment
  pcb::RigidTransform error;      // nominal machine frame -> where the board really lies
  pcb::RigidTransform alignment;  // the job's measured placement (identity: pins only)
  std::vector<std::vector<Point2>> nominal_isolation_mm;  // the job as planned without error
  std::vector<double> measured_mm;
};

struct RunOptions {
  std::string file;                              // the input, named in the report
  std::string name;                              // outputs are OUTDIR/NAME.svg, .json ...
  std::string outdir = "out";                    // made if missing
  bool png = false;                              // the plots as .png too (--png)
  double feed_mm_s = defaults::feed_mm_per_s();  // the plan's, for the report
  double chord_tolerance_mm = defaults::kChordToleranceMm;  // of the controller's points
  double work_w_mm = defaults::work_width_mm(), work_h_mm = defaults::work_height_mm();
  bool realtime = false;
  EncodeOptions encode;
  std::optional<heightmap::SurfaceSpec> surface;  // the simulated blank (--surface)
  // The height map the controller follows (--height-map, checked against the job), or the
  // one --probe writes: map_file is where either is.
  std::optional<heightmap::HeightMap> map;
  std::string map_file;
  // --probe: probes the simulated blank through the sender, writes map_file and returns the
  // map (checked against the job). Needs `surface`.
  std::function<heightmap::HeightMap(Sender&)> probe;
  heightmap::DepthOptions depth;       // V-bit, copper, planned width (its Z: the board's)
  std::optional<PlannedBoard> board;   // the job is this board's
  std::optional<FlipSimulation> flip;  // a board's second setup
  std::function<void(const Progress&)> on_progress;
  // The operator's controls (signals, as send's): called with the sender once the session is
  // open (before probing), nullptr when the simulation ends however it ends.
  std::function<void(Sender*)> attach_controls;
  // Called with the simulated machine's link when the stream ends, however it ends (see
  // sim::SimJobOptions::after_stream): raises the tool after an operator's stop.
  std::function<void(Link&, const SenderOptions&)> after_stream;
};

// The points the firmware core generates for the job's curves, and the bytes the same path
// would take as G-code G1 lines at the same tolerance (for comparison).
struct PointCount {
  size_t points = 0;
  size_t gcode_bytes = 0;
};
PointCount count_points(const JobPlan& plan, double tol_mm);

// Half a pixel of the 1000-pixel plot of the job (zero corner to the far end of the curves).
double plot_step_mm(const JobPlan& plan);

struct RunResult {
  sim::SimJobResult sim;
  PointCount points;
  int pause_confirm_ms = 0;                 // the simulated operator's
  std::optional<heightmap::HeightMap> map;  // the one followed (loaded or probed)
  std::optional<heightmap::SurfaceSpec> surface;
  std::optional<heightmap::DepthReport> depth;  // a board on a simulated blank
  // A board's isolation cuts as simulated, at full resolution and their planned heights
  // (kept, not copied: a large board's paths are many samples).
  std::shared_ptr<sim::CutPathCollector> isolation_cuts;
  std::optional<SimulatedIsolation> isolation;  // check_run()
  std::optional<Registration> registration;     // check_run(), a flip
  std::string base;                             // OUTDIR/NAME
  std::vector<std::string> plot_files;          // write_run_plots(): every picture written
};

// Stage 1: the job through a fresh simulated machine, measured as it runs (the blank, the
// probe, the map, the isolation cuts, the depth of cut). Exit 2 for --probe without a surface.
RunResult simulate_run(const JobPlan& plan, const RunOptions& o);
// Stage 2: BASE.svg (the drawing against the tool path), for a board BASE.board.svg, each
// with a .png when o.png; the depth error and the map's pictures: each named in r->plot_files.
void write_run_plots(const JobPlan& plan, const RunOptions& o, RunResult* r);
// Stage 3: a board's simulated isolation cuts against its copper; a flip's registration.
void check_run(const RunOptions& o, RunResult* r);
// Stage 4: the report (BASE.json, without the depth of cut: the CLI adds it) and its lines.
nlohmann::json run_report_json(const JobPlan& plan, const RunOptions& o, const RunResult& r);
std::string run_report_text(const JobPlan& plan, const RunOptions& o, const RunResult& r);
void write_run_report(const nlohmann::json& report, const RunResult& r);
// Stage 5: ends the command (CommandFailure) when the job did not complete (its outcome's
// code) or the simulated tool cut copper (exit 8).
void refuse_failed_run(const RunOptions& o, const RunResult& r);

// Stages 1 to 3.
RunResult run_job(const JobPlan& plan, const RunOptions& o);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_RUN_COMMAND_H
