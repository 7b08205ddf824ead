// `engraver sim` (the simulated machine on TCP), `engraver send` (stream a drawing to a
// machine) and `engraver run` (both in one process: the main job, with plot and report).
#include <CLI/CLI.hpp>  // CLI::App

#include <fmt/format.h>  // fmt::format

#include <atomic>      // std::atomic
#include <chrono>      // milliseconds
#include <cmath>       // std::round
#include <cstdlib>     // std::strtol
#include <functional>  // std::function
#include <iostream>    // std::cerr
#include <memory>      // std::make_shared
#include <optional>    // std::optional

#include "host/cli/board_cli.h"  // PCB input (Gerber, Excellon, a board's directory)
#include "host/cli/command_registry.h"
#include "host/cli/drawing_read.h"
#include "host/cli/exit_codes.h"
#include "host/cli/height_map_cli.h"     // --surface, --height-map, the depth report
#include "host/cli/operator_controls.h"  // signals and keys
#include "host/cli/option_ranges.h"      // output_folder
#include "host/cli/terminal_text.h"
#include "host/lib/commands/run_command.h"
#include "host/lib/commands/send_command.h"
#include "host/lib/commands/sim_command.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/counted.h"  // counted: "1 hole", "2 holes"
#include "host/lib/plan/job_plan.h"
#include "host/lib/progress/progress_meter.h"
#include "host/lib/stream/link.h"  // parse_link_spec
#include "host/lib/stream/sender.h"

namespace host::cli {

namespace {

struct PlanArgs {
  std::string file;
  double feed_mm_s = defaults::feed_mm_per_s();
  double tol_mm = defaults::kChordToleranceMm;
  double scale = defaults::kScale;
  double margin_mm = defaults::kMarginMm;
  std::vector<double> work_mm{defaults::work_width_mm(), defaults::work_height_mm()};
  double chain_tol_mm = defaults::kChainToleranceMm;
  bool no_reorder = false;
  double z_up_mm = defaults::kZUpMm;
  double z_down_mm = defaults::kZDownMm;
  std::vector<double> offset_mm;  // X Y: drawing coordinates + offset instead of --margin
  std::string tool_side = "centre";
  double tool_radius_mm = 0.0;
  double fit_tol_mm = defaults::kFitToleranceMm;
  bool drill_as_z_moves = false;
  BoardArgs board;
  // Once the command line is read: the input's kind known, its defaults taken and the
  // other kind's options refused (add_plan_options; the command's callback calls it).
  std::function<void()> resolve_input;
};

// Options for drawings only (DXF, G-code): PCB files are cut at their own size and depths.
const char* const kDrawingGroup = "Drawings (DXF, G-code)";

// An option of the other kind of input is refused rather than ignored.
void refuse_options_of_the_other_input(const CLI::App& cmd, bool pcb) {
  for (const CLI::Option* o : cmd.get_options()) {
    if (o->count() == 0) continue;
    if (pcb && o->get_group() == kDrawingGroup)
      throw CLI::ValidationError(o->get_name() + " is for drawings (DXF, G-code), not PCB files");
    if (!pcb && o->get_group() == kBoardOptionsGroup)
      throw CLI::ValidationError(o->get_name() +
                                 " is for PCB files (Gerber, Excellon, a board folder), not "
                                 "drawings");
  }
}

void add_plan_options(CLI::App* cmd, PlanArgs* a) {
  cmd->add_option("FILE", a->file,
                  "drawing (DXF, G-code) or PCB files (Gerber, Excellon, a board folder)")
      ->required();
  CLI::Option* feed =
      cmd->add_option("--feed", a->feed_mm_s,
                      fmt::format("cutting feed in mm/s (PCB isolation: {} unless given)",
                                  defaults::kBoardFeedMmPerS))
          ->capture_default_str();
  CLI::Option* tol =
      cmd->add_option(
             "--tol", a->tol_mm,
             fmt::format("chord tolerance of the generated points in mm (PCB: {} unless given)",
                         defaults::kBoardChordToleranceMm))
          ->capture_default_str();
  CLI::Option* margin =
      cmd->add_option(
             "--margin", a->margin_mm,
             fmt::format("offset of the drawing from the zero corner, mm (PCB: {} unless given)",
                         defaults::kBoardMarginMm))
          ->capture_default_str();
  cmd->add_option("--work", a->work_mm, "work area W H in mm (default A4)")->expected(2);
  cmd->add_option("--z-up", a->z_up_mm, "travel height in mm")->capture_default_str();
  const std::string g = kDrawingGroup;
  cmd->add_option("--scale", a->scale, "scale factor applied to the drawing")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--chain-tol", a->chain_tol_mm, "join curves whose ends are closer, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_flag("--no-reorder", a->no_reorder, "trace curves in drawing order")->group(g);
  cmd->add_option("--z-down", a->z_down_mm, "cutting depth in mm")->group(g)->capture_default_str();
  cmd->add_option("--offset", a->offset_mm,
                  "X Y in mm: machine = drawing + offset (keeps the file's zero; no --margin)")
      ->group(g)
      ->expected(2)
      ->excludes("--margin");
  cmd->add_option("--tool-side", a->tool_side,
                  "cut left or right of the drawn path (tool-radius offset on the controller)")
      ->group(g)
      ->check(one_of({"centre", "left", "right"}))
      ->capture_default_str();
  cmd->add_option("--tool-radius", a->tool_radius_mm, "tool radius in mm for --tool-side")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--fit-tol", a->fit_tol_mm,
                  "G-code: fit runs of short G1 moves within this many mm (0: send each move)")
      ->group(g)
      ->capture_default_str();
  cmd->add_flag("--drill-as-z-moves", a->drill_as_z_moves,
                "G-code drilling cycles as plain Z moves instead of the drill command")
      ->group(g);
  add_board_options(cmd, &a->board);
  // PCB files take `engraver board`'s defaults where no option is given: the board that
  // `board` showed is the board that runs. A missing file is left to the reader to name.
  // Not a parse_complete_callback: CLI11 checks the command's required FILE before one, so
  // `engraver -h run` was "FILE is required" instead of run's help.
  a->resolve_input = [cmd, a, feed, tol, margin] {
    if (!input_exists(a->file)) return;
    const bool pcb = is_pcb_input(a->file);
    refuse_options_of_the_other_input(*cmd, pcb);
    if (!pcb) return;
    refuse_board_option_combinations(a->board);
    const MachineDefaults board;
    if (feed->count() == 0) a->feed_mm_s = board.feed_mm_s;
    if (tol->count() == 0) a->tol_mm = board.chord_tol_mm;
    if (margin->count() == 0) a->margin_mm = board.margin_mm;
  };
}

// A board's job goes to `board` too (when given).
JobPlan load_plan(const PlanArgs& a, Drawing* drawing, commands::PlannedBoard* board = nullptr) {
  if (is_pcb_input(a.file)) {
    MachineDefaults m;
    m.feed_mm_s = a.feed_mm_s;
    m.z_up_mm = a.z_up_mm;
    m.margin_mm = a.margin_mm;
    m.work_w_mm = a.work_mm[0];
    m.work_h_mm = a.work_mm[1];
    m.chord_tol_mm = a.tol_mm;
    return plan_pcb_input(a.file, a.board, m, board);
  }
  *drawing = read_drawing_reporting(a.file);
  for (const std::string& w : drawing->warnings)
    std::cerr << "engraver: warning: " << printable(w) << "\n";
  PlanOptions o;
  o.scale = a.scale;
  o.margin_mm = a.margin_mm;
  o.work_width_mm = a.work_mm[0];
  o.work_height_mm = a.work_mm[1];
  o.reorder = !a.no_reorder;
  o.chain_tolerance_mm = a.chain_tol_mm;
  o.feed_mm_per_s = a.feed_mm_s;
  o.z_up_mm = a.z_up_mm;
  o.z_down_mm = a.z_down_mm;
  if (a.offset_mm.size() == 2) {
    o.fixed_offset = true;
    o.offset_mm = Point2(a.offset_mm[0], a.offset_mm[1]);
  }
  o.tool_side = a.tool_side == "left"    ? ToolSide::kLeft
                : a.tool_side == "right" ? ToolSide::kRight
                                         : ToolSide::kCentre;
  if (o.tool_side != ToolSide::kCentre && !(a.tool_radius_mm > 0)) {
    throw CLI::ValidationError("--tool-side " + a.tool_side + " needs --tool-radius MM above 0");
  }
  o.tool_radius_mm = a.tool_radius_mm;
  o.fit_tolerance_mm = a.fit_tol_mm;
  o.drill_mode = a.drill_as_z_moves ? DrillMode::kZMoves : DrillMode::kDrillCommand;
  // Each stage of planning its own line (ordering, the work-area check, the steps): the
  // later ones took most of a 200 000-line drawing's time with no line.
  StagedProgress bar("plan", std::cerr, ProgressMeter::for_stderr());
  o.progress = [&bar](const char* unit, size_t done, size_t total) {
    bar.update(unit, done, total);
  };
  try {
    // The drawing's curves are handed over (callers need only the plan and the program).
    JobPlan plan = plan_job(std::move(*drawing), o);
    bar.update("curves made into steps", plan.curves.size(), plan.curves.size());
    return plan;
  } catch (const PlanError& e) {
    throw PlanError(fmt::format("{}: {}", a.file, e.what()));
  }
}

EncodeOptions encode_options(const PlanArgs& a) {
  EncodeOptions e;
  e.chord_tolerance_um = static_cast<uint16_t>(std::lround(a.tol_mm * 1000.0));
  e.title = input_name(a.file);
  return e;
}

// What a progress line says about the machine: state, position and (simulated) time.
// With the job progress (the INDEX:POINT that --resume-at takes after a controller restart).
std::string machine_detail(const Progress& p) {
  std::string s = fmt::format("{} at ({:.1f}, {:.1f}) mm", machine_state_name(p.status.state),
                              p.status.x_um / 1000.0, p.status.y_um / 1000.0);
  if (p.status.flags & proto::kStatusJob)
    s += fmt::format(", job {}:{}", p.status.job_index, p.status.curve_point);
  return s;
}

// ---- engraver send ----

struct SendArgs {
  PlanArgs plan;
  HeightMapArgs map;
  std::string to;
  bool no_zero = false;
  int poll_ms = 250;
  bool resume = false;    // continue from where the controller says the job stopped
  std::string resume_at;  // INDEX[:POINT]: continue from there (after a controller restart)
};

// While a job streams: the keys, and the progress bar (ended before the job's last line).
struct Streaming {
  Streaming(Sender& sender, std::optional<ProgressMeter>* bar) : keys(sender), bar_(bar) {
    bar_->emplace("send", "commands", std::cerr, ProgressMeter::for_stderr());
  }
  ~Streaming() { bar_->reset(); }
  Keyboard keys;
  std::optional<ProgressMeter>* bar_;
};

// Binds send's options to the library's send_job and says how the job ended.
void run_send(const SendArgs& a) {
  commands::SendOptions o;
  // A bad resume point before anything else.
  if (!a.resume_at.empty()) o.resume_at = commands::parse_resume_at(a.resume_at);
  o.resume = a.resume;
  Drawing drawing;
  commands::PlannedBoard board;  // PCB input: where its probe probes
  board.with_probe_area = a.map.probe;
  const JobPlan plan = load_plan(a.plan, &drawing, &board);
  // A map from a file is checked against the job before anything is sent.
  o.map = load_height_map(a.map);
  if (o.map) refuse_job_leaving_map(plan, *o.map, a.map.height_map);
  const std::string probe_map_path =
      a.map.height_map.empty() ? default_map_path(".", input_name(a.plan.file)) : a.map.height_map;
  if (a.map.probe) check_map_writable(probe_map_path);  // before anything moves
  o.encode = encode_options(a.plan);
  if (o.resume_at) commands::check_resume_at(plan, o.encode, *o.resume_at);  // before the link
  const LinkSpec spec = parse_link_spec(a.to);  // LinkError -> usage error below
  std::unique_ptr<Link> link = open_link(spec, std::chrono::milliseconds(5000));
  o.file = a.plan.file;
  o.sender.zero_first = !a.no_zero;
  o.sender.status_interval = std::chrono::milliseconds(a.poll_ms);
  if (a.map.probe) {
    o.probe = [&, path = probe_map_path](Sender& sender) {
      heightmap::HeightMap map =
          probe_raising_on_interrupt(sender, *link, o.sender, plan, a.map, a.plan.z_up_mm, path,
                                     board.probe_area, kExitRefused);
      refuse_job_leaving_map(plan, map, path);
      return map;
    };
  }
  o.attach_controls = signals_to;
  std::optional<ProgressMeter> bar;
  o.while_streaming = [&bar](Sender& sender) { return std::make_shared<Streaming>(sender, &bar); };
  o.on_progress = [&bar](const Progress& p) {
    if (bar)
      bar->update(p.executed, p.total, machine_detail(p),
                  machine_waits_for_operator(p.status.state));
  };
  const commands::SendResult r = commands::send_job(*link, plan, o, std::cerr);
  if (r.outcome == JobOutcome::kCompleted) return;
  // Ctrl-C (INT/TERM) stopped the machine where it was, maybe at depth: the tool goes up as
  // in run and probe (a new session; the job's progress stays for --resume).
  const std::string lifted = raise_tool_if_abort_signalled(*link, o.sender, a.plan.z_up_mm);
  throw CommandFailure(commands::exit_code_of(r.outcome),
                       commands::send_ending_text(r) + (lifted.empty() ? "" : "; " + lifted));
}

// ---- engraver probe ----

struct ProbeArgs {
  PlanArgs plan;
  HeightMapArgs map;
  std::string to;
  bool no_zero = false;
};

void run_probe(const ProbeArgs& a) {
  Drawing drawing;
  commands::PlannedBoard board;  // PCB input: where its probe probes
  board.with_probe_area = true;
  const JobPlan plan = load_plan(a.plan, &drawing, &board);
  const std::string path =
      a.map.height_map.empty() ? default_map_path(".", input_name(a.plan.file)) : a.map.height_map;
  check_map_writable(path);  // before the machine moves, not after every point is probed
  const LinkSpec spec = parse_link_spec(a.to);
  std::unique_ptr<Link> link = open_link(spec, std::chrono::milliseconds(5000));
  SenderOptions so;
  so.zero_first = !a.no_zero;
  Sender sender(*link, so);
  sender.open_session();
  if (a.no_zero) commands::refuse_unzeroed_machine(sender, "probe");
  signals_to(&sender);
  std::cerr << fmt::format(
      "engraver: probing the blank under {} through {}: the probe clip on the blank, the "
      "spindle off\n",
      a.plan.file, link->name());
  try {
    probe_raising_on_interrupt(sender, *link, so, plan, a.map, a.plan.z_up_mm, path,
                               board.probe_area, kExitRefused);
  } catch (const CommandFailure&) {
    signals_to(nullptr);
    throw;
  }
  signals_to(nullptr);
}

// ---- engraver sim ----

struct SimArgs {
  std::string surface;  // --surface: the simulated blank
  std::string listen = "127.0.0.1:10001";
  bool realtime = false;
  std::string trace;
  int pause_confirm_ms = sim::SimOptions{}.pause_confirm_ms;
};

std::atomic<bool> g_stop_sim{false};

void run_sim(const SimArgs& a) {
  commands::SimCommandOptions o;
  o.listen = a.listen;
  o.realtime = a.realtime;
  o.trace = a.trace;
  o.blank = surface_spec_of(a.surface);
  o.pause_confirm_ms = a.pause_confirm_ms;
  signals_stop(&g_stop_sim);
  const commands::SimCommandResult r = commands::run_sim(o, g_stop_sim, std::cerr);
  if (!r.trace_ok) std::cerr << fmt::format("engraver: --trace: '{}': write failed\n", a.trace);
  std::cerr << fmt::format(
      "engraver: simulated {:.1f} s of machine time; {} confirmed by the simulated "
      "operator; spindle {} ({})\n",
      r.machine_ms / 1000.0, counted(r.pauses_confirmed, "pause"), r.spindle_on ? "on" : "off",
      counted(r.spindle_switches, "switching"));
}

// ---- engraver run ----

struct RunArgs {
  PlanArgs plan;
  std::string outdir = "out";
  bool realtime = false;
  bool png = false;                 // the plots as PNG too
  std::vector<double> blank_error;  // DX DY DEG: the flipped blank placed off by this much
  bool pins_only = false;           // with blank_error: no measured alignment
  std::string surface;              // --surface: the simulated blank
  HeightMapArgs map;
};

// A double-sided board's second setup: plans the nominal job, places the blank off by the
// error and, unless pins only, re-plans the job onto the holes as the simulated operator
// measures them (to the micrometre).
JobPlan plan_flip(const RunArgs& a, commands::FlipSimulation* f, commands::PlannedBoard* board) {
  Drawing drawing;
  JobPlan plan = load_plan(a.plan, &drawing, board);
  const pcb::BoardJob* nominal = board->job.get();
  const std::vector<Point2> holes = nominal ? nominal->alignment_holes_mm : std::vector<Point2>{};
  if (holes.size() < 2)
    throw CommandFailure(kExitUsage,
                         "--blank-error simulates a double-sided board's second setup: give the "
                         "board job its --align-holes");
  if (!a.plan.board.alignment.measured_mm.empty())
    throw CommandFailure(kExitUsage,
                         "--blank-error measures the holes itself: leave out --align-measured");
  f->dx_mm = a.blank_error[0];
  f->dy_mm = a.blank_error[1];
  f->rotation_deg = a.blank_error[2];
  f->pins_only = a.pins_only;
  f->nominal_isolation_mm = commands::isolation_paths_mm(*nominal);
  f->error = pcb::placement_error((holes[0] + holes[1]) / 2, f->dx_mm, f->dy_mm, f->rotation_deg);
  if (a.pins_only) return plan;
  PlanArgs aligned = a.plan;
  for (size_t i = 0; i < 2; ++i) {
    const Point2 m = f->error.apply(holes[i]);
    for (double v : {m.x(), m.y()})
      aligned.board.alignment.measured_mm.push_back(std::round(v * 1000) / 1000);
  }
  f->measured_mm = aligned.board.alignment.measured_mm;
  plan = load_plan(aligned, &drawing, board);
  f->alignment = board->job->frame.placement;
  return plan;
}

// Run's options as the library takes them (the plan is made already).
commands::RunOptions run_options(const RunArgs& a, const JobPlan& plan,
                                 const commands::PlannedBoard& board) {
  commands::RunOptions o;
  o.file = a.plan.file;
  o.name = input_name(a.plan.file);
  o.outdir = a.outdir;
  o.png = a.png;
  o.feed_mm_s = a.plan.feed_mm_s;
  o.chord_tolerance_mm = a.plan.tol_mm;
  o.work_w_mm = a.plan.work_mm[0];
  o.work_h_mm = a.plan.work_mm[1];
  o.realtime = a.realtime;
  o.encode = encode_options(a.plan);
  o.surface = surface_spec_of(a.surface);
  if (board.job) o.board = board;
  o.depth.vbit_angle_deg = a.map.vbit_angle_deg;
  o.depth.copper_um = a.map.copper_um;
  o.depth.planned_width_um = a.plan.board.isolation.tool_width_mm * 1000.0;
  // The controller follows a map from a file (checked against the job first) or probed.
  o.map = load_height_map(a.map);
  if (o.map) refuse_job_leaving_map(plan, *o.map, a.map.height_map);
  o.map_file = a.map.probe && a.map.height_map.empty() ? default_map_path(a.outdir, o.name)
                                                       : a.map.height_map;
  if (a.map.probe && o.surface) {  // without a blank, simulate_run refuses --probe
    std::filesystem::create_directories(a.outdir);
    check_map_writable(o.map_file);
  }
  if (a.map.probe) {
    o.probe = [&a, &plan, path = o.map_file, area = board.probe_area](Sender& sender) {
      heightmap::HeightMap map = probe_for_job(sender, plan, a.map, a.plan.z_up_mm, path, area);
      refuse_job_leaving_map(plan, map, path);
      return map;
    };
  }
  return o;
}

// Stages: plan (and a flip's second plan), simulate, plot, check, report, refuse a failed job.
void run_run(const RunArgs& a) {
  JobPlan plan;
  commands::PlannedBoard board;  // PCB input: its board job
  board.with_probe_area = a.map.probe;
  std::optional<commands::FlipSimulation> flip;
  if (!a.blank_error.empty()) {
    flip.emplace();
    plan = plan_flip(a, &*flip, &board);
  } else {
    Drawing drawing;  // only the plan is needed from here on
    plan = load_plan(a.plan, &drawing, &board);
  }
  commands::RunOptions o = run_options(a, plan, board);
  o.flip = flip;
  // Ctrl-C (INT/TERM) stops the simulated machine as send stops the real one (#X), and the
  // tool goes up: while probing and while the job runs.
  o.attach_controls = signals_to;
  std::string lifted;  // what the lift after a Ctrl-C did
  o.after_stream = [&lifted, z = a.plan.z_up_mm](Link& link, const SenderOptions& so) {
    lifted = raise_tool_if_abort_signalled(link, so, z);
  };
  commands::RunResult r = [&o, &plan, &lifted] {
    ProgressMeter bar("run", "commands", std::cerr, ProgressMeter::for_stderr());
    o.on_progress = [&bar](const Progress& p) {
      bar.update(p.executed, p.total, machine_detail(p),
                 machine_waits_for_operator(p.status.state));
    };
    try {
      commands::RunResult result = commands::simulate_run(plan, o);
      o.on_progress = nullptr;
      return result;
    } catch (const CommandFailure& e) {
      if (lifted.empty()) throw;
      throw CommandFailure(e.code, fmt::format("probing stopped: {} ({})", lifted, e.what()));
    }
  }();
  // Stopped by a signal (Ctrl-C, SIGTERM) before the job ended: the figures so far are
  // written, marked stopped; half a job is not checked for copper it left uncut.
  const bool stopped = !lifted.empty() && r.sim.outcome != JobOutcome::kCompleted;
  if (!lifted.empty() && !stopped) {
    std::cerr << "engraver: run stopped: " << r.sim.message << "; " << lifted << "\n";
  }
  commands::write_run_plots(plan, o, &r);
  if (!stopped) commands::check_run(o, &r);
  nlohmann::json report = commands::run_report_json(plan, o, r);
  if (stopped) report["stopped"] = true;
  if (r.depth) report["depth_of_cut"] = depth_report_json(*r.depth, r.map.has_value());
  commands::write_run_report(report, r);
  std::cout << commands::run_report_text(plan, o, r);
  if (r.depth) std::cout << depth_report_text(*r.depth, r.map.has_value());
  if (stopped) {  // the last line says how the run ended, once
    throw CommandFailure(
        commands::exit_code_of(r.sim.outcome),
        fmt::format("run stopped: {}; {}; the plot and the report ({}.json, \"stopped\": true) "
                    "show the job so far (a run starts afresh: nothing to resume)",
                    r.sim.message, lifted, r.base));
  }
  commands::refuse_failed_run(o, r);
}

// The machine a command talks to: --to (required) and --no-zero.
void add_link_options(CLI::App* cmd, std::string* to, bool* no_zero) {
  // A malformed address is a bad command line (exit 2) before anything is planned, not a
  // lost link (6) after it.
  const CLI::Validator link_address(
      [](const std::string& spec) -> std::string {
        try {
          parse_link_spec(spec);
          return "";
        } catch (const LinkError& e) {
          return e.what();
        }
      },
      "", "link");
  cmd->add_option(
         "--to", *to,
         "tcp://HOST:PORT, the port always given, in decimal (0080 is 80; an XPort listens "
         "on 10001 unless set up otherwise; IPv6 in brackets: tcp://[::1]:10001) or "
         "serial:DEVICE[,BAUD]")
      ->required()
      ->check(link_address);
  cmd->add_flag("--no-zero", *no_zero,
                "do not start manual zeroing: a machine that is not zeroed is refused (exit 1) "
                "before anything is sent");
}

// Runs the command with its arguments (its input's options resolved first); a link that
// fails ends it with kExitLinkLost.
template <class Args>
void callback_ending_on_link_errors(CLI::App* cmd, std::shared_ptr<Args> args,
                                    void (*run)(const Args&)) {
  cmd->callback([args, run] {
    args->plan.resolve_input();
    try {
      run(*args);
    } catch (const LinkError& e) {
      throw CommandFailure(kExitLinkLost, e.what());
    }
  });
}

void add_send_command(CLI::App& app) {
  auto send_args = std::make_shared<SendArgs>();
  CLI::App* send = app.add_subcommand("send", "plan a drawing and stream it to the machine");
  add_plan_options(send, &send_args->plan);
  add_height_map_options(send, &send_args->map, HeightMapCommand::kSend);
  add_link_options(send, &send_args->to, &send_args->no_zero);
  send->add_option("--poll-ms", send_args->poll_ms,
                   "status poll interval (keep-alive); 0 = one query always in flight")
      ->capture_default_str();
  send->add_flag("--resume", send_args->resume,
                 "continue the job from where the controller says it stopped (lost link, abort, "
                 "alarm); give the same file and plan options as the first send");
  send->add_option("--resume-at", send_args->resume_at,
                   "INDEX[:POINT]: continue from job command INDEX (curve point POINT), e.g. "
                   "after a controller restart, from the last progress line's 'job' figures "
                   "(digits only; checked against the planned job before the link is opened)")
      ->excludes("--resume");
  send->footer(
      "Example: engraver send board.dxf --to tcp://192.168.1.50:10001 --feed 8\n"
      "After a lost link: engraver send board.dxf --to ... --feed 8 --resume\n"
      "Keys: h hold, r resume, x abort, +/- feed override. Signals: INT/TERM abort (then the "
      "tool goes up to --z-up; --resume continues), USR1 hold, USR2 resume.\nExit: 0 done, 1 "
      "job refused, 2 bad input, 3 aborted, 4 alarm, "
      "5 command refused by the controller (or Ctrl-C while --probe touches), 6 link lost, 7 "
      "stalled (no progress for 30 s), 8 a "
      "board job that would cut copper (refused before streaming).");
  callback_ending_on_link_errors(send, send_args, run_send);
}

void add_probe_command(CLI::App& app) {
  auto probe_args = std::make_shared<ProbeArgs>();
  CLI::App* probe =
      app.add_subcommand("probe", "probe the blank on a grid over a job and write its height map");
  add_plan_options(probe, &probe_args->plan);
  add_height_map_options(probe, &probe_args->map, HeightMapCommand::kProbe);
  add_link_options(probe, &probe_args->to, &probe_args->no_zero);
  probe->footer(
      "Example: engraver probe board/ --to tcp://192.168.1.50:10001 --height-map board.map.json\n"
      "then: engraver send board/ --to ... --height-map board.map.json\n"
      "Exit: 0 map written, 1 probing refused (a point disagreeing with its neighbours, two "
      "touches apart, heights spanning more than 1 mm; --no-zero and the machine not zeroed), 2 "
      "bad input or options, 5 the "
      "controller refused the probe (no contact, spindle on, probe closed) or Ctrl-C/SIGTERM "
      "stopped a touch (the tool is raised), 6 link lost.");
  callback_ending_on_link_errors(probe, probe_args, run_probe);
}

void add_sim_command(CLI::App& app) {
  auto sim_args = std::make_shared<SimArgs>();
  CLI::App* sim = app.add_subcommand("sim", "run the simulated machine on a TCP port");
  sim->add_option("--listen", sim_args->listen,
                  "ADDR:PORT (loopback by default; a numeric address, IPv6 in brackets: "
                  "[::1]:10001; PORT in decimal, 080 is 80, 0 any free port), or serial:DEVICE "
                  "(a tty or a pty)")
      ->capture_default_str();
  sim->add_flag("--realtime", sim_args->realtime, "machine time always follows the wall clock");
  sim->add_option("--trace", sim_args->trace,
                  "write the executed tool positions as CSV: t_ms,x_mm,y_mm,z_mm,pen,wall_ms");
  add_surface_option(sim, &sim_args->surface);
  sim->add_option("--pause-confirm-ms", sim_args->pause_confirm_ms,
                  "the simulated operator confirms a pause (#P) after this long; -1 never")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](const std::string& v) -> std::string {
            const long ms = std::strtol(v.c_str(), nullptr, 10);
            return ms == -1 || (ms >= 0 && ms <= 3600000)
                       ? ""
                       : v + " is outside the allowed range 0 .. 3600000 ms (or -1: never)";
          },
          "-1 or 0 .. 3600000 ms", "pause"));
  sim->footer(
      "Examples:\n"
      "  engraver sim --trace path.csv & engraver send samples/engraver-word.dxf --to "
      "tcp://127.0.0.1:10001\n"
      "  socat pty,raw,echo=0,link=/tmp/sim-tty pty,raw,echo=0,link=/tmp/host-tty &\n"
      "  engraver sim --listen serial:/tmp/sim-tty & engraver send board.dxf --to "
      "serial:/tmp/host-tty\n"
      "Clock: fast while the host talks, the wall clock's pace after 500 ms of machine time "
      "without a byte from it (docs/user-guide.md). The link's time-outs count the wall "
      "clock whatever the pace, as on the machine: a partial frame is dropped after 200 ms "
      "without a byte, a running machine holds after 2 s without a valid frame.\n"
      "Exit: 0 stopped, 2 bad option or address.");
  sim->callback([sim_args] { run_sim(*sim_args); });
}

void add_run_command(CLI::App& app) {
  auto run_args = std::make_shared<RunArgs>();
  CLI::App* run = app.add_subcommand(
      "run",
      "the main job: simulate the machine and send the drawing to it (in lockstep, one "
      "process)");
  add_plan_options(run, &run_args->plan);
  run->add_option("-o,--outdir", run_args->outdir, "where NAME.svg/.json (and .png) go")
      ->check(output_folder())
      ->capture_default_str();
  run->add_flag("--png", run_args->png, "also write the plots as PNG (NAME.png, NAME.board.png)");
  run->add_flag("--realtime", run_args->realtime, "simulate in real time");
  run->add_option("--blank-error", run_args->blank_error,
                  "double-sided, second setup: DX DY DEG, the simulated machine's flipped blank "
                  "sits this far off on its pins (mm, mm, degrees about the holes' middle); the "
                  "simulated operator measures the alignment holes and the job is aligned to "
                  "them; the report gives the registration error")
      ->expected(3);
  run->add_flag("--pins-only", run_args->pins_only,
                "with --blank-error: no measured alignment (the pins alone)")
      ->needs("--blank-error");  // alone it would be ignored without a word
  add_surface_option(run, &run_args->surface);
  add_height_map_options(run, &run_args->map, HeightMapCommand::kRun);
  // The simulated probe touches the simulated blank: without one, refused as the command line
  // is read (not after planning), in the words of the other options that need another.
  run->get_option("--probe")->needs("--surface");
  run->footer(
      "Example: engraver run samples/engraver-word.dxf -o out\n"
      "Progress on stderr (a bar on a terminal, a line every 5 s otherwise).\n"
      "Ctrl-C or SIGTERM stops the simulated machine (#X) and raises the tool (exit 3; while "
      "--probe touches, exit 5 as probe); a stopped job's plot and report show it so far, "
      "the report marked \"stopped\": true.\n"
      "Exit: 0 done, 1 job refused, 2 bad input, 3 aborted, 4 alarm, 5 command refused by "
      "the controller or a touch stopped, 6 link lost, 7 stalled (no progress for 30 s of "
      "machine time), 8 a board job whose controller points or simulated path cut copper.");
  callback_ending_on_link_errors(run, run_args, run_run);
}

void add_machine_commands(CLI::App& app) {
  add_send_command(app);
  add_probe_command(app);
  add_sim_command(app);
  add_run_command(app);
}

const CommandRegistrar registrar("machine", {"send", "probe", "sim", "run"}, add_machine_commands);

}  // namespace

}  // namespace host::cli
