// `engraver run` as a function, stage by stage (see run_command.h).
#include "host/lib/commands/run_command.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>   // std::max, std::min
#include <cmath>       // std::lround, std::isnan, M_PI
#include <filesystem>  // create_directories
#include <fstream>     // std::ofstream
#include <memory>      // std::shared_ptr

#include "host/lib/commands/board_command.h"  // narrow_gaps_json
#include "host/lib/commands/exit_codes.h"
#include "host/lib/commands/send_command.h"      // exit_code_of
#include "host/lib/heightmap/controller_map.h"   // job_map_commands
#include "host/lib/heightmap/simulated_blank.h"  // the blank the simulated probe touches
#include "host/lib/pcb/board_check.h"            // refuse_copper_hits
#include "host/lib/pcb/isolation_check.h"        // describe
#include "host/lib/plan/counted.h"               // counted: "1 hole", "2 holes"
#include "host/lib/plan/firmware_points.h"
#include "host/lib/plot/board_plot.h"
#include "host/lib/plot/height_map_plot.h"
#include "host/lib/plot/plan_plot.h"
#include "host/lib/plot/plot.h"

namespace host::commands {

PointCount count_points(const JobPlan& plan, double tol_mm) {
  PointCount n;
  // Curve by curve, so nothing of the job's size is kept.
  for (const PlannedCurve& c : plan.curves) {
    for (const Point2& p :
         firmware_points_mm(c.spline(), static_cast<int>(std::lround(tol_mm * 1000)))) {
      ++n.points;
      n.gcode_bytes += fmt::formatted_size("G1 X{:.3f} Y{:.3f}\n", p.x(), p.y());
    }
  }
  return n;
}

double plot_step_mm(const JobPlan& plan) {
  const Extents& e = plan.extents_mm;
  if (e.empty()) return 0.05;
  const double span =
      std::max(e.max.x() - std::min(0.0, e.min.x()), e.max.y() - std::min(0.0, e.min.y()));
  return std::max(0.005, span / 2000.0);
}

namespace {

// The simulated blank: from the zero corner to the job's far end and as far again as the
// margin (the work area for an empty job).
std::optional<heightmap::SurfaceModel> blank_under_job(const JobPlan& plan, const RunOptions& o) {
  if (!o.surface) return std::nullopt;
  const Extents& e = plan.extents_mm;
  return heightmap::SurfaceModel(
      *o.surface, e.empty() ? heightmap::AreaMm{0, 0, o.work_w_mm, o.work_h_mm}
                            : heightmap::AreaMm{0, 0, e.max.x() + std::max(0.0, e.min.x()),
                                                e.max.y() + std::max(0.0, e.min.y())});
}

// What is measured while the job runs; lives as long as the simulation.
struct RunMeters {
  std::optional<heightmap::SurfaceModel> surface;
  std::shared_ptr<heightmap::SimulatedBlank> blank;  // the simulated probe touches it
  bool job_started = false;  // measured from the job's first command on (not the probing's)
  // A board: the isolation cuts at full resolution, to check them against the copper (at
  // their planned height: the map's height taken off again), and their depth of cut.
  std::shared_ptr<sim::CutPathCollector> isolation_cuts;
  std::optional<heightmap::DepthMeter> depth;
};

void add_sample(RunMeters& m, const std::optional<heightmap::HeightMap>& map,
                const sim::ToolSample& s) {
  if (m.blank) m.blank->tool_at(s.x_mm, s.y_mm, s.z_mm);
  if (!m.job_started || !m.isolation_cuts) return;
  sim::ToolSample planned = s;
  if (map) planned.z_mm -= map->interpolate_um(s.x_mm, s.y_mm) / 1000.0;
  m.isolation_cuts->add(planned);
  if (m.depth) m.depth->add(s.x_mm, s.y_mm, s.z_mm);
}

// The height map's part of the run: the controller follows it (loaded, or probed first).
void follow_map(const RunOptions& o, RunMeters& m, std::optional<heightmap::HeightMap>& map,
                sim::SimJobOptions* so) {
  if (o.probe || map) {
    so->z_offset_mm = [&map](double x_mm, double y_mm) {
      return map ? map->interpolate_um(x_mm, y_mm) / 1000.0 : 0.0;
    };
  }
  // The job's map, or a clear without one, goes just before the job (as with send).
  so->before_job = [&o, &m, &map](Sender& sender) {
    if (o.attach_controls) o.attach_controls(&sender);
    if (o.probe) {
      map = o.probe(sender);
      if (m.depth) m.depth->set_applied_map(&*map);
    }
    m.job_started = true;
    return heightmap::job_map_commands(map ? &*map : nullptr);
  };
}

}  // namespace

RunResult simulate_run(const JobPlan& plan, const RunOptions& o) {
  RunResult r;
  r.map = o.map;
  r.surface = o.surface;
  RunMeters m;
  m.surface = blank_under_job(plan, o);
  if (o.probe && !m.surface)
    throw CommandFailure(kExitUsage,
                         "run --probe needs a simulated blank to touch: give --surface too");
  sim::SimJobOptions so;
  so.encode = o.encode;
  so.realtime = o.realtime;
  // Polled as `send` polls the real machine (every 250 ms, here of machine time), so the
  // frames and bytes reported are those a real run would put on the wire.
  so.sender.status_interval = std::chrono::milliseconds(250);
  // The plot shows what its pixels can: keep a tool position every half pixel or so.
  so.trace_step_mm = plot_step_mm(plan);
  if (m.surface) {
    m.blank = std::make_shared<heightmap::SimulatedBlank>(*m.surface);
    so.machine.surface_um = [blank = m.blank](int32_t x_um, int32_t y_um) {
      return blank->surface_um(x_um, y_um);
    };
  }
  m.job_started = !o.probe;
  if (const std::optional<double> z = o.board ? o.board->checked_isolation_z_mm() : std::nullopt) {
    m.isolation_cuts = std::make_shared<sim::CutPathCollector>(*z, 0.002);
    if (m.surface) {
      heightmap::DepthOptions d = o.depth;
      d.isolation_z_mm = *z;
      m.depth.emplace(*m.surface, r.map ? &*r.map : nullptr, d);  // --probe: set when probed
    }
  }
  so.on_sample = [&m, &r](const sim::ToolSample& s) { add_sample(m, r.map, s); };
  r.base = (std::filesystem::path(o.outdir) / o.name).string();
  std::filesystem::create_directories(o.outdir);
  follow_map(o, m, r.map, &so);
  so.on_progress = [&o](Sender&, const Progress& p) {
    if (o.on_progress) o.on_progress(p);
  };
  so.after_stream = [&o](Link& link, const SenderOptions& sender) {
    if (o.attach_controls) o.attach_controls(nullptr);  // before the sender is gone
    if (o.after_stream) o.after_stream(link, sender);
  };
  r.sim = sim::run_sim_job(plan, so);
  r.pause_confirm_ms = so.machine.pause_confirm_ms;
  r.isolation_cuts = m.isolation_cuts;
  if (m.depth) r.depth = m.depth->report();
  r.points = count_points(plan, o.chord_tolerance_mm);
  return r;
}

void write_run_plots(const JobPlan& plan, const RunOptions& o, RunResult* r) {
  const std::string& base = r->base;
  std::vector<std::string>& written = r->plot_files;
  written.clear();
  // The drawing's curves against the simulated tool path (lent to the plots, then kept).
  PlotInput plot = plot_input_from_plan(plan, o.name, 0.01, false);
  plot.tool_path = std::move(r->sim.plot_path);
  write_plot(plot, base + ".svg", o.png ? base + ".png" : "");
  written.push_back(base + ".svg");
  if (o.png) written.push_back(base + ".png");
  if (o.board && o.board->job) {  // copper, isolation width, holes
    BoardPlotInput in;
    in.title = o.board->title + " (simulated)";
    in.job = o.board->job.get();
    in.simulated = std::move(plot.tool_path);
    write_board_plot(in, base + ".board.svg", o.png ? base + ".board.png" : "");
    plot.tool_path = std::move(in.simulated);
    written.push_back(base + ".board.svg");
    if (o.png) written.push_back(base + ".board.png");
  }
  if (r->depth) {
    write_depth_error_svg(r->depth->kept, 50.0, o.name, base + ".depth.svg");
    written.push_back(base + ".depth.svg");
  }
  if (r->map && !o.probe) {
    write_height_map_svg(*r->map, o.name, base + ".map.svg");
    written.push_back(base + ".map.svg");
  }
  r->sim.plot_path = std::move(plot.tool_path);
}

void check_run(const RunOptions& o, RunResult* r) {
  if (!r->isolation_cuts) return;
  const std::vector<std::vector<Point2>>& cuts = r->isolation_cuts->paths();
  const size_t samples = r->isolation_cuts->samples();
  const PlannedBoard& board = *o.board;
  if (!o.flip) {
    r->isolation = check_simulated_isolation(*board.job, board.check_tolerance_mm, cuts, samples);
    return;
  }
  // Where the cuts land on the board: back through the placement error; then into the frame
  // the job was planned in, for the check against its copper.
  const FlipSimulation& flip = *o.flip;
  r->registration = registration_error(cuts, flip.error, flip.nominal_isolation_mm);
  const pcb::RigidTransform back = flip.error.inverse();
  std::vector<std::vector<Point2>> on_copper = cuts;
  for (std::vector<Point2>& path : on_copper)
    for (Point2& p : path) p = flip.alignment.apply(back.apply(p));
  r->isolation =
      check_simulated_isolation(*board.job, board.check_tolerance_mm, on_copper, samples);
}

namespace {

nlohmann::json isolation_json(const SimulatedIsolation& iso) {
  nlohmann::json j = {
      {"tolerance_mm", iso.tolerance_mm},
      {"paths", iso.paths},
      {"samples", iso.samples},
      {"islands", iso.check.islands},
      {"copper_hits", iso.check.hits.size()},
      {"unseparated_pairs", iso.check.unseparated.size()},
      {"min_clearance_um", iso.min_clearance_um},
      {"planned_min_clearance_um", iso.planned_min_clearance_um},
      {"min_clearance_at_mm", {iso.min_clearance_at_mm.x(), iso.min_clearance_at_mm.y()}}};
  if (!std::isnan(iso.clearing_min_clearance_um))
    j["clearing_tool_min_clearance_um"] = iso.clearing_min_clearance_um;
  return j;
}

nlohmann::json flip_json(const FlipSimulation& flip) {
  return {{"blank_error",
           {{"dx_mm", flip.dx_mm}, {"dy_mm", flip.dy_mm}, {"rotation_deg", flip.rotation_deg}}},
          {"measured_holes_mm", flip.measured_mm},
          {"aligned", !flip.pins_only},
          {"alignment",
           {{"rotation_deg", flip.alignment.rotation_rad * 180 / M_PI},
            {"shift_mm", {flip.alignment.shift_mm.x(), flip.alignment.shift_mm.y()}}}}};
}

std::string joined(const std::vector<std::string>& files) {
  std::string s;
  for (const std::string& f : files) s += (s.empty() ? "" : ", ") + f;
  return s;
}

// The commands sent before the job's own (the height map, or its clearing): the progress
// line's total counts them too.
std::string setup_text(const sim::SimJobResult& s) {
  if (s.setup.commands == 0) return "";
  return fmt::format(" (and {} before the job: the height map or its clearing)",
                     counted(s.setup.commands, "set-up command"));
}

// "sent 111 commands", or for a job that ended early how far it got: "7 of 112 commands
// executed (the set-up included) of a job of 111 commands".
std::string commands_text(const sim::SimJobResult& s) {
  const size_t all = s.commands + s.setup.commands;
  if (s.outcome == JobOutcome::kCompleted || s.executed >= all) {
    return "sent " + counted(s.commands, "command");
  }
  return fmt::format("{} of {} executed{}, of a job of {}", s.executed, counted(all, "command"),
                     s.setup.commands > 0 ? " (the set-up included)" : "",
                     counted(s.commands, "command"));
}

double speedup(uint64_t machine_ms, double s) {
  return s > 0 ? machine_ms / 1000.0 / s : 0.0;
}

}  // namespace

nlohmann::json run_report_json(const JobPlan& plan, const RunOptions& o, const RunResult& r) {
  const sim::SimJobResult& s = r.sim;
  nlohmann::json j;
  j["drawing"] = o.file;
  j["outcome"] = outcome_name(s.outcome);
  j["message"] = s.message;
  j["curves"] = plan.curves.size();
  j["pen_lifts"] = plan.pen_lifts;
  j["commands"] = s.commands;
  j["setup_commands"] = s.setup.commands;  // before the job; progress total = both
  j["commands_executed"] = s.executed;     // of both: all of them when completed
  j["frames_sent"] = s.stats.frames_sent;
  j["bytes_sent"] = s.stats.bytes_sent;
  j["job_wire_bytes"] = s.wire_bytes;
  j["job_id"] = s.job_id;
  j["gcode_g1_bytes_same_tolerance"] = r.points.gcode_bytes;
  j["retransmits"] = s.stats.retransmits;
  j["status_queries"] = s.stats.status_queries;
  j["points_generated"] = r.points.points;
  j["planned_cut_mm"] = plan.cut_length_mm;
  j["planned_rapid_mm"] = plan.rapid_length_mm;
  j["traced_cut_mm"] = s.cut_mm;
  j["traced_rapid_mm"] = s.rapid_mm;
  j["feed_mm_per_s"] = o.feed_mm_s;
  j["chord_tolerance_mm"] = o.chord_tolerance_mm;
  j["simulated_job_s"] = s.motion_s;
  j["simulated_cut_s"] = s.cut_s;
  j["cut_length_over_feed_s"] = plan.cut_length_mm / o.feed_mm_s;
  j["max_contour_error_um"] = s.max_contour_error_um;
  j["max_contour_error_at_mm"] = {s.worst_contour_sample.x_mm, s.worst_contour_sample.y_mm};
  if (r.depth) j["surface"] = heightmap::surface_spec_text(*r.surface);
  if (r.map) {
    j["height_map"] = {{"file", o.map_file},
                       {"rows", r.map->rows},
                       {"cols", r.map->cols},
                       {"min_um", r.map->min_um()},
                       {"max_um", r.map->max_um()},
                       {"frames", s.setup.commands},
                       {"wire_bytes", s.setup.wire_bytes}};
  }
  if (r.isolation) j["simulated_isolation_check"] = isolation_json(*r.isolation);
  if (o.board && o.board->job) {
    // As `board` reports them: why there is no cut-out, what the planner left out.
    j["no_cutout"] = o.board->job->report.no_cutout;
    j["notes"] = o.board->job->report.notes;
    j["narrow_gaps"] = narrow_gaps_json(o.board->job->report.narrow_gaps);
  }
  if (o.flip) {
    j["flip"] = flip_json(*o.flip);
    if (r.registration)
      j["registration_error"] = {{"max_um", r.registration->max_um},
                                 {"mean_um", r.registration->mean_um},
                                 {"samples", r.registration->samples}};
  }
  j["plot_tool_path"] = {{"samples_kept", s.plot_path.size()},
                         {"samples_simulated", s.trace_samples},
                         {"step_mm", s.trace_step_mm}};
  j["simulated_machine_ms"] = s.virtual_ms;
  j["wall_s"] = s.wall_s;
  j["speedup_vs_real_time"] = speedup(s.virtual_ms, s.wall_s);
  j["simulator_cpu_s"] = s.cpu_s;
  j["speedup_per_cpu_second"] = speedup(s.virtual_ms, s.cpu_s);
  j["lcd"] = {s.lcd[0], s.lcd[1]};
  j["pauses_confirmed_by_simulated_operator"] = s.pauses_confirmed;
  j["pause_confirm_ms"] = r.pause_confirm_ms;
  j["spindle_on_at_end"] = s.spindle_on;
  return j;
}

void write_run_report(const nlohmann::json& report, const RunResult& r) {
  std::ofstream out(r.base + ".json");
  out << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

std::string run_report_text(const JobPlan& plan, const RunOptions& o, const RunResult& r) {
  const sim::SimJobResult& s = r.sim;
  const std::string& base = r.base;
  std::string t = fmt::format(
      "{}: {}, {}; job {}\n"
      "  {}{} in {}, {} bytes ({} resent after busy or loss); the job as "
      "frames: {} bytes, "
      "as G-code G1 at the same tolerance: {} bytes\n"
      "  tool path {:.1f} mm cut + {:.1f} mm rapid; simulated job time {:.1f} s, of which "
      "cutting {:.1f} s (cut length / feed {:.1f} s)\n"
      "  max contour error {:.1f} um at ({:.3f}, {:.3f}) mm on the machine; simulated {:.1f} s of "
      "machine time in {:.2f} s ({:.2f} s of processor time: {:.0f}x real time)\n"
      "  {} confirmed by the simulated operator ({} ms after each); spindle {} at the "
      "end\n"
      "  plot: {}; report: {}.json\n",
      o.file, counted(plan.curves.size(), "curve"), counted(plan.pen_lifts, "pen lift"),
      outcome_name(s.outcome), commands_text(s), setup_text(s),
      counted(s.stats.frames_sent, "frame"), s.stats.bytes_sent, s.stats.retransmits, s.wire_bytes,
      r.points.gcode_bytes, s.cut_mm, s.rapid_mm, s.motion_s, s.cut_s,
      plan.cut_length_mm / o.feed_mm_s, s.max_contour_error_um, s.worst_contour_sample.x_mm,
      s.worst_contour_sample.y_mm, s.virtual_ms / 1000.0, s.wall_s, s.cpu_s,
      speedup(s.virtual_ms, s.cpu_s), counted(s.pauses_confirmed, "pause"), r.pause_confirm_ms,
      s.spindle_on ? "on" : "off", joined(r.plot_files), base);
  if (o.board && o.board->job) {
    if (!o.board->job->report.no_cutout.empty())
      t += "  no cut-out: " + o.board->job->report.no_cutout + "\n";
    for (const std::string& n : o.board->job->report.notes) t += "  note: " + n + "\n";
  }
  if (s.trace_step_mm > plot_step_mm(plan))
    t += fmt::format(
        "  the plot's tool path is thinned to {:.3f} mm steps ({} of {} samples kept, a long "
        "job)\n",
        s.trace_step_mm, s.plot_path.size(), s.trace_samples);
  if (const std::optional<SimulatedIsolation>& iso = r.isolation) {
    t += fmt::format(
        "  simulated isolation cuts ({}, {}) against the copper: {} "
        "beyond {:.3f} mm, {}; least clearance of the tool's edge {:.1f} um "
        "at ({:.3f}, {:.3f}) mm on the machine (planned paths: {:.1f} um)\n",
        counted(iso->paths, "path"), counted(iso->samples, "sample"),
        counted(iso->check.hits.size(), "copper hit"), iso->tolerance_mm,
        counted(iso->check.unseparated.size(), "unseparated pair"), iso->min_clearance_um,
        iso->min_clearance_at_mm.x(), iso->min_clearance_at_mm.y(), iso->planned_min_clearance_um);
    // Which pairs (and hits), as `board` lists them: a count alone left the user to guess.
    const std::string listed = pcb::describe(iso->check);  // a count line, then one a finding
    for (size_t at = listed.find('\n'); at != std::string::npos;) {
      const size_t next = listed.find('\n', at + 1);
      t += "  " + listed.substr(at + 1, next == std::string::npos ? next : next - at - 1) + "\n";
      at = next;
    }
  }
  if (r.registration) {
    const FlipSimulation& f = *o.flip;
    t += fmt::format(
        "  double-sided: blank placed off by ({:.3f}, {:.3f}) mm and {:.2f} deg; {}; the cuts "
        "land {:.1f} um (max, mean {:.1f} um) from where they belong on the board\n",
        f.dx_mm, f.dy_mm, f.rotation_deg,
        f.pins_only ? "pins only, no measured alignment" : "the job aligned to the measured holes",
        r.registration->max_um, r.registration->mean_um);
  }
  return t;
}

void refuse_failed_run(const RunOptions& o, const RunResult& r) {
  if (r.sim.outcome != JobOutcome::kCompleted) {
    throw CommandFailure(exit_code_of(r.sim.outcome),
                         fmt::format("job {}: {}", outcome_name(r.sim.outcome), r.sim.message));
  }
  if (!r.isolation) return;
  // The simulated machine cut copper: the real one would too.
  try {
    pcb::refuse_copper_hits(r.isolation->check, "the simulated tool path");
  } catch (const pcb::CopperCutError& e) {
    throw CommandFailure(kExitCutsCopper, o.name + ": " + e.what());
  }
}

RunResult run_job(const JobPlan& plan, const RunOptions& o) {
  RunResult r = simulate_run(plan, o);
  write_run_plots(plan, o, &r);
  check_run(o, &r);
  return r;
}

}  // namespace host::commands
