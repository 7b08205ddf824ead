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
void add_height_map_options(CLI::App* cmd, HeightMapArgs* args, bool report_options);
// The map from --height-map (not --probe); a bad file is a usage error naming it.
std::optional<heightmap::HeightMap> load_height_map(const HeightMapArgs& args);

// The depth report as the run's JSON and its printed lines.
nlohmann::json depth_report_json(const heightmap::DepthReport& r, bool compensated);
std::string depth_report_text(const heightmap::DepthReport& r, bool compensated);

}  // namespace host::cli

#endif  // HOST_CLI_HEIGHT_MAP_CLI_H
