// Height map options and the depth report's words (height_map_cli.h).
#include "host/cli/height_map_cli.h"

#include <fmt/format.h>  // fmt::format

#include <filesystem>  // std::filesystem::path
#include <fstream>     // std::ofstream
#include <iostream>    // std::cerr
#include <sstream>     // std::stringstream

#include "host/cli/exit_codes.h"
#include "host/cli/operator_controls.h"  // raise_tool_if_abort_signalled
#include "host/cli/option_ranges.h"      // number_refusal
#include "host/lib/heightmap/controller_map.h"
#include "host/lib/heightmap/job_area.h"
#include "host/lib/heightmap/probe_session.h"
#include "host/lib/plan/counted.h"  // counted: "1 hole", "2 holes"
#include "host/lib/plot/height_map_plot.h"
#include "host/lib/progress/progress_meter.h"

namespace host::cli {

namespace {

// Each number of the spec ("tilt=0.1mm", "bump=X:Y:R:H", "seed=1") as the other number
// options take them: a plain, finite decimal (the spec's reader, like strtod, takes hex
// floats). "" when every number is one, else "ITEM: 'v' is not a decimal number".
std::string surface_number_refusal(const std::string& text) {
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos) continue;  // the reader names it
    std::stringstream values(item.substr(eq + 1));
    std::string v;
    while (std::getline(values, v, ':')) {
      std::string number = v;
      for (const char* unit : {"mm", "um"})
        if (number.size() > 2 && number.compare(number.size() - 2, 2, unit) == 0)
          number.resize(number.size() - 2);
      const std::string refused = number_refusal(number);
      if (!refused.empty()) return item + ": " + refused;
    }
  }
  return "";
}

// The refusal of a spec without the option's name ("tilt=0.1: give the length with its
// unit ..."), "" for a good one: CLI11 puts "--surface: " in front, as for every option.
std::string surface_refusal(const std::string& text) {
  const std::string refused = surface_number_refusal(text);
  if (!refused.empty()) return refused;
  try {
    heightmap::parse_surface_spec(text);
  } catch (const heightmap::SurfaceSpecError& e) {
    std::string m = e.what();
    const std::string name = "--surface";
    if (m.compare(0, name.size(), name) == 0) m.erase(0, name.size());
    if (m.compare(0, 2, ": ") == 0 || m.compare(0, 1, " ") == 0)
      m.erase(0, m.find_first_not_of(": "));
    return m;
  }
  return "";
}

}  // namespace

void add_surface_option(CLI::App* cmd, std::string* surface) {
  // Checked while the command line is read, before anything is planned.
  cmd->add_option("--surface", *surface,
                  "simulated blank: tilt=0.1mm,tilt_y=0um,bow=0.2mm,bump=X:Y:R:H,noise=2um,"
                  "seed=1,area=X0:Y0:X1:Y1 (each length with mm or um; docs/user-guide.md)")
      ->check(CLI::Validator([](std::string& v) { return surface_refusal(v); }, "", "surface"))
      ->group(kHeightMapGroup);
}

std::optional<heightmap::SurfaceSpec> surface_spec_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const std::string refused = surface_refusal(text);
  if (!refused.empty()) throw CommandFailure(kExitUsage, "--surface: " + refused);
  return heightmap::parse_surface_spec(text);
}

void add_height_map_options(CLI::App* cmd, HeightMapArgs* a, HeightMapCommand command) {
  const std::string g = kHeightMapGroup;
  if (command == HeightMapCommand::kProbe) {
    a->probe = true;
    cmd->add_option("--height-map", a->height_map,
                    "where the map is written (JSON; default NAME.map.json here)")
        ->group(g);
  } else {
    cmd->add_option("--height-map", a->height_map,
                    "the blank's height map (JSON): the controller follows it; with --probe, "
                    "where the probed map is written (default NAME.map.json)")
        ->group(g);
    cmd->add_flag("--probe", a->probe, "probe the blank on a grid over the job first")->group(g);
  }
  cmd->add_option("--probe-spacing", a->grid.spacing_mm,
                  "largest distance between probe points, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--probe-grid", a->grid_rows_cols, "ROWS COLS: exactly this grid (2..16 each)")
      ->group(g)
      ->expected(2)
      ->excludes("--probe-spacing");
  cmd->add_option("--probe-margin", a->grid.margin_mm,
                  "the grid reaches this far beyond the job, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_flag("--probe-twice", a->probe_twice,
                "probe every point twice (the map records the repeatability)")
      ->group(g);
  cmd->add_option("--outlier-limit", a->outlier_limit_um,
                  "a point further than this from its neighbours' prediction is probed again, "
                  "then refused, um")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--blank", a->blank, "the blank's name, kept in the map")->group(g);
  if (command != HeightMapCommand::kRun) return;
  cmd->add_option("--vbit-angle", a->vbit_angle_deg,
                  "V-bit included angle in degrees (the depth report's groove width)")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--copper-um", a->copper_um, "copper thickness in um (the depth report)")
      ->group(g)
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

std::string default_map_path(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / (name + ".map.json")).string();
}

std::string map_picture_path(const std::string& map_path) {
  const std::string json = ".json";
  if (map_path.size() > json.size() &&
      map_path.compare(map_path.size() - json.size(), json.size(), json) == 0)
    return map_path.substr(0, map_path.size() - json.size()) + ".svg";
  return map_path + ".svg";
}

void check_map_writable(const std::string& map_path) {
  // The map is written beside its path and renamed (write_height_map_file), the picture
  // directly: both files must be creatable in that directory.
  for (const std::string& path : {map_path + ".part", map_picture_path(map_path) + ".part"}) {
    std::error_code ec;
    const bool fresh = !std::filesystem::exists(path, ec);
    bool ok = std::filesystem::path(map_path).has_filename() &&
              !std::filesystem::is_directory(map_path, ec);
    if (ok) {
      std::ofstream probe(path, std::ios::app);
      ok = static_cast<bool>(probe);
    }
    if (fresh) std::filesystem::remove(path, ec);
    if (!ok)
      throw CommandFailure(kExitUsage,
                           fmt::format("{}: cannot write the height map there; nothing was "
                                       "probed (give --height-map a file in a writable folder)",
                                       map_path));
  }
}

// The controller refused the probe (its alarm): send/run's "command refused" (exit 5).
constexpr int kExitProbeRefusedByController = 5;

heightmap::HeightMap probe_for_job(Sender& sender, const JobPlan& plan, const HeightMapArgs& a,
                                   double z_up_mm, const std::string& map_path,
                                   const std::optional<heightmap::AreaMm>& board_area) {
  const std::optional<heightmap::AreaMm> area =
      board_area ? board_area : heightmap::cutting_area(plan);
  if (!area) throw CommandFailure(kExitUsage, "the job cuts nothing: there is nothing to probe");
  heightmap::ProbeOptions o;
  o.grid = a.grid;
  if (a.grid_rows_cols.size() == 2) {
    o.grid.rows = a.grid_rows_cols[0];
    o.grid.cols = a.grid_rows_cols[1];
  }
  o.twice = a.probe_twice;
  o.outlier_limit_um = a.outlier_limit_um;
  o.blank = a.blank;
  heightmap::ProbeMotion m;
  m.travel_z_mm = z_up_mm;
  heightmap::ProbeRun run;
  try {
    ProgressMeter bar("probe", "touches", std::cerr, ProgressMeter::for_stderr());
    run = heightmap::probe_blank(*area, o, heightmap::controller_touch(sender, m),
                                 [&bar](size_t done, size_t total) { bar.update(done, total); });
  } catch (const heightmap::GridError& e) {
    throw CommandFailure(kExitUsage, std::string("probe grid: ") + e.what());
  } catch (const heightmap::ProbeFailed& e) {
    // A touch that ended because the link went silent is a lost link, as for a job.
    throw CommandFailure(e.link_lost() ? kExitLinkLost : kExitProbeRefusedByController, e.what());
  } catch (const heightmap::ProbeRefused& e) {
    throw CommandFailure(kExitJobFailed, std::string("probing refused: ") + e.what());
  } catch (const heightmap::HeightMapError& e) {
    throw CommandFailure(kExitJobFailed, std::string("probing refused: ") + e.what());
  }
  for (const std::string& r : run.reprobed) std::cerr << "engraver: probed again: " << r << "\n";
  const heightmap::HeightMap& map = run.map;
  try {
    heightmap::write_height_map_file(map, map_path);
    write_height_map_svg(map, std::filesystem::path(map_path).stem().string(),
                         map_picture_path(map_path));
  } catch (const std::runtime_error& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
  std::cerr << fmt::format(
      "engraver: probed {} x {} points ({}), heights {:.1f} .. {:.1f} um{}; map {}, "
      "picture {}\n",
      map.rows, map.cols, counted(run.touches, "touch", "touches"), map.min_um(), map.max_um(),
      map.repeatability_um ? fmt::format(", repeatability {:.1f} um", *map.repeatability_um)
                           : std::string(),
      map_path, map_picture_path(map_path));
  return map;
}

heightmap::HeightMap probe_raising_on_interrupt(Sender& sender, Link& link,
                                                const SenderOptions& options, const JobPlan& plan,
                                                const HeightMapArgs& a, double z_up_mm,
                                                const std::string& map_path,
                                                const std::optional<heightmap::AreaMm>& area,
                                                int interrupted_exit) {
  try {
    return probe_for_job(sender, plan, a, z_up_mm, map_path, area);
  } catch (const CommandFailure& e) {
    // Ctrl-C stopped the touch where it was (#X), maybe on the copper: the tool up first.
    const std::string lifted = raise_tool_if_abort_signalled(link, options, z_up_mm);
    if (lifted.empty()) throw;
    // One last line, as the guide prints it: what stopped, then where the touch was.
    throw CommandFailure(interrupted_exit,
                         fmt::format("probing stopped: {} ({})", lifted, e.what()));
  }
}

void refuse_job_leaving_map(const JobPlan& plan, const heightmap::HeightMap& map,
                            const std::string& what) {
  try {
    heightmap::refuse_job_outside_map(plan, map, what);
  } catch (const heightmap::HeightMapError& e) {
    throw CommandFailure(kExitJobFailed, e.what());
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
