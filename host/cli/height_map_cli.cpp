// Height map options and the depth report's words (height_map_cli.h).
#include "host/cli/height_map_cli.h"

#include <fmt/format.h>  // fmt::format

#include "host/cli/exit_codes.h"

namespace host::cli {

void add_surface_option(CLI::App* cmd, std::string* surface) {
  cmd->add_option("--surface", *surface,
                  "simulated blank: tilt=0.1mm,tilt_y=0um,bow=0.2mm,bump=X:Y:R:H,noise=2um,"
                  "seed=1,area=X0:Y0:X1:Y1 (each length with mm or um; docs/user-guide.md)")
      ->group(kHeightMapGroup);
}

std::optional<heightmap::SurfaceSpec> surface_spec_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  try {
    return heightmap::parse_surface_spec(text);
  } catch (const heightmap::SurfaceSpecError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

void add_height_map_options(CLI::App* cmd, HeightMapArgs* a, bool report_options) {
  const std::string g = kHeightMapGroup;
  cmd->add_option("--height-map", a->height_map,
                  "the blank's height map (JSON): the controller follows it; with --probe, "
                  "where the probed map is written")
      ->group(g);
  cmd->add_flag("--probe", a->probe, "probe the blank on a grid over the job first")->group(g);
  cmd->add_option("--probe-spacing", a->grid.spacing_mm,
                  "largest distance between probe points, mm")
      ->group(g)
      ->check(CLI::Range(1.0, 65.0))
      ->capture_default_str();
  cmd->add_option("--probe-grid", a->grid_rows_cols, "ROWS COLS: exactly this grid (2..16 each)")
      ->group(g)
      ->expected(2)
      ->excludes("--probe-spacing");
  cmd->add_option("--probe-margin", a->grid.margin_mm,
                  "the grid reaches this far beyond the job, mm")
      ->group(g)
      ->check(CLI::Range(0.0, 50.0))
      ->capture_default_str();
  cmd->add_flag("--probe-twice", a->probe_twice,
                "probe every point twice (the map records the repeatability)")
      ->group(g);
  cmd->add_option("--outlier-limit", a->outlier_limit_um,
                  "a point further than this from its neighbours' prediction is probed again, "
                  "then refused, um")
      ->group(g)
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--blank", a->blank, "the blank's name, kept in the map")->group(g);
  if (!report_options) return;
  cmd->add_option("--vbit-angle", a->vbit_angle_deg,
                  "V-bit included angle in degrees (the depth report's groove width)")
      ->group(g)
      ->check(CLI::Range(5.0, 150.0))
      ->capture_default_str();
  cmd->add_option("--copper-um", a->copper_um, "copper thickness in um (the depth report)")
      ->group(g)
      ->check(CLI::Range(1.0, 500.0))
      ->capture_default_str();
}

std::optional<heightmap::HeightMap> load_height_map(const HeightMapArgs& a) {
  if (a.height_map.empty() || a.probe) return std::nullopt;
  try {
    return heightmap::read_height_map_file(a.height_map);
  } catch (const heightmap::HeightMapError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

nlohmann::json depth_report_json(const heightmap::DepthReport& r, bool compensated) {
  return {{"compensated_with_height_map", compensated},
          {"isolation_samples", r.samples},
          {"isolation_length_mm", r.length_mm},
          {"planned_depth_um", r.planned_depth_um},
          {"depth_min_um", r.min_depth_um},
          {"depth_max_um", r.max_depth_um},
          {"max_depth_error_um", r.max_error_um},
          {"max_depth_error_at_mm", {r.max_error_at_mm[0], r.max_error_at_mm[1]}},
          {"rms_depth_error_um", r.rms_error_um},
          {"planned_groove_width_um", r.planned_width_um},
          {"groove_width_min_um", r.min_width_um},
          {"groove_width_max_um", r.max_width_um},
          {"max_groove_width_error_um", r.max_width_error_um},
          {"copper_not_cut_through_mm", r.uncut_mm},
          {"copper_not_cut_through_share", r.uncut_share}};
}

std::string depth_report_text(const heightmap::DepthReport& r, bool compensated) {
  return fmt::format(
      "  depth of cut against the simulated blank ({}): {:.1f} mm of isolation, depth {:.1f} .. "
      "{:.1f} um (planned {:.1f}); max error {:+.1f} um at ({:.3f}, {:.3f}) mm, RMS {:.1f} um\n"
      "  V-bit groove width {:.1f} .. {:.1f} um (planned {:.1f}, worst {:+.1f} um); copper not "
      "cut through along {:.1f} mm ({:.1f} % of the isolation)\n",
      compensated ? "with the height map" : "no height map", r.length_mm, r.min_depth_um,
      r.max_depth_um, r.planned_depth_um, r.max_error_um, r.max_error_at_mm[0],
      r.max_error_at_mm[1], r.rms_error_um, r.min_width_um, r.max_width_um, r.planned_width_um,
      r.max_width_error_um, r.uncut_mm, 100.0 * r.uncut_share);
}

}  // namespace host::cli
