// The height map on the command line: `--surface` (the simulated blank, for `sim` and
// `run`), `--height-map FILE` / `--probe` (compensate a job, for `run` and `send`), and the
// depth-of-cut report `run` prints for a board on a simulated blank.
#ifndef HOST_CLI_HEIGHT_MAP_CLI_H
#define HOST_CLI_HEIGHT_MAP_CLI_H

#include <CLI/CLI.hpp>  // CLI::App

#include <nlohmann/json.hpp>  // nlohmann::json
#include <optional>           // std::optional
#include <string>             // std::string

#include "host/lib/heightmap/depth_meter.h"
#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/probe_grid.h"
#include "host/lib/heightmap/surface_model.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/stream/sender.h"

namespace host::cli {

inline constexpr const char* kHeightMapGroup = "Height map (warped blanks)";

// `--surface TEXT` of `sim` and `run`: the simulated blank (surface_model.h).
void add_surface_option(CLI::App* cmd, std::string* surface);
// The spec, or nullopt for ""; a bad text is a usage error (CommandFailure, exit 2).
std::optional<heightmap::SurfaceSpec> surface_spec_of(const std::string& text);

// How a run/send gets its map: from a file, or by probing first.
struct HeightMapArgs {
  std::string height_map;  // --height-map FILE: compensate with this map (or write it: --probe)
  bool probe = false;      // --probe: probe the grid first, then compensate
  heightmap::GridOptions grid;
  std::vector<int> grid_rows_cols;  // --probe-grid ROWS COLS
  bool probe_twice = false;
  double outlier_limit_um = 25;
  std::string blank;
  // The report of `run`: the V-bit and the copper.
  double vbit_angle_deg = 30;
  double copper_um = 35;
};
// `probe` itself has no --probe (it always probes) and only `run` has the report's options.
enum class HeightMapCommand { kProbe, kSend, kRun };
void add_height_map_options(CLI::App* cmd, HeightMapArgs* args, HeightMapCommand command);
// The map from --height-map (not --probe); a bad file is a usage error naming it.
std::optional<heightmap::HeightMap> load_height_map(const HeightMapArgs& args);

// NAME.map.json in `dir` (probe, send: the current directory; run: its outdir).
std::string default_map_path(const std::string& dir, const std::string& name);
// The map's picture beside it: board.map.json -> board.map.svg.
std::string map_picture_path(const std::string& map_path);

// Before any motion of a probing: the map (and its picture) can be written at map_path,
// else a usage error (exit 2) saying nothing was probed.
void check_map_writable(const std::string& map_path);

// Probes the blank over the job's cutting area through the sender (zeroing it first if it
// is not), says what was probed again, writes the map to `map_path` and its picture, and
// returns it. Ends the command (CommandFailure) with exit 1 when the probing is refused (an
// outlier, two touches apart, the span), 2 for a grid the options cannot make or a map that
// cannot be written, 5 when the controller refuses the probe (its alarm); a LinkError passes.
// area: where to probe (a board's pcb::board_probe_area); nullopt: where the plan cuts.
heightmap::HeightMap probe_for_job(Sender& sender, const JobPlan& plan, const HeightMapArgs& a,
                                   double z_up_mm, const std::string& map_path,
                                   const std::optional<heightmap::AreaMm>& area);
// probe_for_job on a real machine, whose Ctrl-C (SIGINT, SIGTERM: the signalled sender's
// abort, #X) stops the touch under way where it is: the tool then goes up to z_up_mm over
// `link` (a new session: heightmap::raise_tool_after_abort), saying so, and the failure
// exits `interrupted_exit` (`probe` 5, `send --probe` 3: aborted).
heightmap::HeightMap probe_raising_on_interrupt(Sender& sender, Link& link,
                                                const SenderOptions& options, const JobPlan& plan,
                                                const HeightMapArgs& a, double z_up_mm,
                                                const std::string& map_path,
                                                const std::optional<heightmap::AreaMm>& area,
                                                int interrupted_exit);
// Exit 1 (nothing sent) when the job cuts outside the map.
void refuse_job_leaving_map(const JobPlan& plan, const heightmap::HeightMap& map,
                            const std::string& what);

// The depth report as the run's JSON and its printed lines.
nlohmann::json depth_report_json(const heightmap::DepthReport& r, bool compensated);
std::string depth_report_text(const heightmap::DepthReport& r, bool compensated);

}  // namespace host::cli

#endif  // HOST_CLI_HEIGHT_MAP_CLI_H
