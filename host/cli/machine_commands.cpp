// `engraver sim` (the simulated machine on TCP), `engraver send` (stream a drawing to a
// machine) and `engraver run` (both in one process: the main job, with plot and report).
#include <CLI/CLI.hpp>  // CLI::App

#include <fmt/format.h>       // fmt::format
#include <signal.h>           // sigaction
#include <termios.h>          // raw keyboard
#include <unistd.h>           // isatty, read
#include <nlohmann/json.hpp>  // nlohmann::json

#include <atomic>      // std::atomic
#include <chrono>      // steady_clock
#include <cmath>       // std::round, M_PI
#include <filesystem>  // create_directories
#include <fstream>     // std::ofstream
#include <iostream>    // std::cerr
#include <optional>    // std::optional
#include <thread>      // keyboard thread
#include <utility>     // std::pair

#include "firmware/config/machine_config.h"
#include "host/cli/board_cli.h"  // PCB input (Gerber, Excellon, a board's directory)
#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/cli/height_map_cli.h"  // --surface, --height-map, the depth report
#include "host/cli/terminal_text.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/heightmap/controller_map.h"   // height_map_commands
#include "host/lib/heightmap/simulated_blank.h"  // the blank the simulated probe touches
#include "host/lib/pcb/board_check.h"            // refuse_copper_hits
#include "host/lib/plan/firmware_points.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/plot/height_map_plot.h"
#include "host/lib/plot/plan_plot.h"
#include "host/lib/plot/plot.h"
#include "host/lib/progress/progress_meter.h"
#include "host/lib/sim/cut_paths.h"
#include "host/lib/sim/sim_job.h"
#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/job_resume.h"
#include "host/lib/stream/sender.h"

namespace host::cli {

namespace {

int exit_code(JobOutcome outcome) {
  switch (outcome) {
    case JobOutcome::kCompleted:
      return kExitOk;
    case JobOutcome::kAborted:
      return kExitAborted;
    case JobOutcome::kAlarm:
      return kExitAlarm;
    case JobOutcome::kRejected:
      return kExitRefused;
    case JobOutcome::kLinkLost:
      return kExitLinkLost;
    case JobOutcome::kStalled:
      return kExitStalled;
  }
  return kExitJobFailed;
}

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
          ->check(CLI::Range(0.1, 60.0))
          ->capture_default_str();
  CLI::Option* tol =
      cmd->add_option(
             "--tol", a->tol_mm,
             fmt::format("chord tolerance of the generated points in mm (PCB: {} unless given)",
                         defaults::kBoardChordToleranceMm))
          ->check(CLI::Range(0.001, 1.0))
          ->capture_default_str();
  CLI::Option* margin =
      cmd->add_option(
             "--margin", a->margin_mm,
             fmt::format("offset of the drawing from the zero corner, mm (PCB: {} unless given)",
                         defaults::kBoardMarginMm))
          ->check(CLI::Range(0.0, 100.0))
          ->capture_default_str();
  cmd->add_option("--work", a->work_mm, "work area W H in mm (default A4)")->expected(2);
  cmd->add_option("--z-up", a->z_up_mm, "travel height in mm")->capture_default_str();
  const std::string g = kDrawingGroup;
  cmd->add_option("--scale", a->scale, "scale factor applied to the drawing")
      ->group(g)
      ->check(CLI::Range(1e-3, 1e3))
      ->capture_default_str();
  cmd->add_option("--chain-tol", a->chain_tol_mm, "join curves whose ends are closer, mm")
      ->group(g)
      ->check(CLI::Range(0.0, 1.0))
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
      ->check(CLI::IsMember({"centre", "left", "right"}))
      ->capture_default_str();
  cmd->add_option("--tool-radius", a->tool_radius_mm, "tool radius in mm for --tool-side")
      ->group(g)
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--fit-tol", a->fit_tol_mm,
                  "G-code: fit runs of short G1 moves within this many mm (0: send each move)")
      ->group(g)
      ->check(CLI::Range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_flag("--drill-as-z-moves", a->drill_as_z_moves,
                "G-code drilling cycles as plain Z moves instead of the drill command")
      ->group(g);
  add_board_options(cmd, &a->board);
  // PCB files take `engraver board`'s defaults where no option is given: the board that
  // `board` showed is the board that runs. A missing file is left to the reader to name.
  cmd->parse_complete_callback([cmd, a, feed, tol, margin] {
    if (!input_exists(a->file)) return;
    const bool pcb = is_pcb_input(a->file);
    refuse_options_of_the_other_input(*cmd, pcb);
    if (!pcb) return;
    const MachineDefaults board;
    if (feed->count() == 0) a->feed_mm_s = board.feed_mm_s;
    if (tol->count() == 0) a->tol_mm = board.chord_tol_mm;
    if (margin->count() == 0) a->margin_mm = board.margin_mm;
  });
}

JobPlan load_plan(const PlanArgs& a, Drawing* drawing) {
  if (is_pcb_input(a.file)) {
    MachineDefaults m;
    m.feed_mm_s = a.feed_mm_s;
    m.z_up_mm = a.z_up_mm;
    m.margin_mm = a.margin_mm;
    m.work_w_mm = a.work_mm[0];
    m.work_h_mm = a.work_mm[1];
    m.chord_tol_mm = a.tol_mm;
    return plan_pcb_input(a.file, a.board, m);
  }
  *drawing = import_drawing(a.file);
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
  ProgressMeter bar("plan", "curves ordered", std::cerr, ProgressMeter::for_stderr());
  o.progress = [&bar](size_t done, size_t total) { bar.update(done, total); };
  try {
    // The drawing's curves are handed over (callers need only the plan and the program).
    JobPlan plan = plan_job(std::move(*drawing), o);
    bar.update(plan.curves.size(), plan.curves.size());
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

// ---- Operator controls: signals and keys ----

Sender* g_sender = nullptr;  // for the signal handlers (request_* only set atomics)

extern "C" void on_signal(int sig) {
  if (g_sender == nullptr) return;
  if (sig == SIGUSR1)
    g_sender->request_hold();
  else if (sig == SIGUSR2)
    g_sender->request_resume();
  else
    g_sender->request_abort();
}

void install_signals(Sender* sender) {
  g_sender = sender;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGUSR1, SIGUSR2}) sigaction(sig, &sa, nullptr);
}

// Keys while a job runs (stdin a terminal): h hold, r resume, x abort, + / - override.
class Keyboard {
 public:
  explicit Keyboard(Sender& sender) : sender_(sender) {
    if (!isatty(STDIN_FILENO)) return;
    tcgetattr(STDIN_FILENO, &saved_);
    termios raw = saved_;
    raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 1;  // read() returns every 100 ms so the thread can stop
    tcsetattr(STDIN_FILENO, TCSANOW, &raw);
    active_ = true;
    thread_ = std::thread([this] { loop(); });
  }
  ~Keyboard() {
    if (!active_) return;
    stop_ = true;
    thread_.join();
    tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
  }

 private:
  void loop() {
    int override_pct = 100;
    while (!stop_) {
      char c;
      if (read(STDIN_FILENO, &c, 1) != 1) continue;
      if (c == 'h' || c == ' ') sender_.request_hold();
      if (c == 'r') sender_.request_resume();
      if (c == 'x' || c == 'q') sender_.request_abort();
      if (c == '+' || c == '-') {
        override_pct = std::max(10, std::min(200, override_pct + (c == '+' ? 10 : -10)));
        sender_.request_override(override_pct);
      }
    }
  }
  Sender& sender_;
  termios saved_{};
  bool active_ = false;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

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

// "12" or "12:40" -> job index and curve point; throws CommandFailure on anything else.
std::pair<int32_t, uint16_t> parse_resume_at(const std::string& text) {
  const size_t colon = text.find(':');
  try {
    size_t used = 0;
    const long index = std::stol(text.substr(0, colon), &used);
    if (used != text.substr(0, colon).size() || index < 0) throw std::invalid_argument(text);
    long point = 0;
    if (colon != std::string::npos) {
      point = std::stol(text.substr(colon + 1), &used);
      if (used != text.size() - colon - 1 || point < 0 || point > 65535)
        throw std::invalid_argument(text);
    }
    return {static_cast<int32_t>(index), static_cast<uint16_t>(point)};
  } catch (const std::exception&) {
    throw CommandFailure(kExitUsage,
                         fmt::format("--resume-at '{}': expected INDEX or INDEX:POINT (job "
                                     "command and curve point, as the progress line shows them)",
                                     text));
  }
}

// send --resume / --resume-at: the stream that continues the job instead of the whole job.
std::vector<QueuedCommand> resume_stream(const SendArgs& a, Sender& sender,
                                         const std::vector<QueuedCommand>& job,
                                         const EncodeOptions& enc) {
  // The new session stopped what was left: where it came to rest is where to go on.
  const proto::StatusReply status = sender.read_status_at_rest(std::chrono::seconds(30));
  std::optional<ResumePoint> at;
  if (!a.resume_at.empty()) {
    const auto [index, point] = parse_resume_at(a.resume_at);  // checked before connecting
    at = resume_point_at(job, index, point, status.z_um);
  } else {
    at = resume_point_of(status);
    if (at && !resume_mismatch(job, *at).empty())
      throw CommandFailure(kExitJobFailed, resume_mismatch(job, *at));
    if (!at) {
      throw CommandFailure(
          kExitJobFailed,
          "the controller reports no job progress (it was restarted or never ran a job): zero it "
          "at the job's zero point again and use --resume-at INDEX:POINT with the 'job' figures "
          "of the last progress line");
    }
  }
  std::cerr << fmt::format("engraver: resuming at {}; the tool goes to ({:.3f}, {:.3f}) mm\n",
                           describe_resume_point(job, *at), at->x_um / 1000.0, at->y_um / 1000.0);
  return resume_commands(job, *at, enc);
}

void run_send(const SendArgs& a) {
  if (!a.resume_at.empty()) parse_resume_at(a.resume_at);  // a bad one before anything else
  Drawing drawing;
  const JobPlan plan = load_plan(a.plan, &drawing);
  // A map from a file is checked against the job before anything is sent.
  std::optional<heightmap::HeightMap> map = load_height_map(a.map);
  if (map) refuse_job_leaving_map(plan, *map, a.map.height_map);
  const LinkSpec spec = parse_link_spec(a.to);  // LinkError -> usage error below
  std::unique_ptr<Link> link = open_link(spec, std::chrono::milliseconds(5000));
  SenderOptions so;
  so.zero_first = !a.no_zero;
  so.status_interval = std::chrono::milliseconds(a.poll_ms);
  Sender sender(*link, so);
  install_signals(&sender);
  const proto::SessionReply caps = sender.open_session();
  EncodeOptions enc = encode_options(a.plan);
  use_session(caps, &enc);
  enc.controller = &caps;
  std::vector<QueuedCommand> commands = encode_job(plan, enc);
  const uint16_t job_id = job_id_of(commands);  // the whole job's, also when resumed
  if (a.resume || !a.resume_at.empty()) {
    commands = resume_stream(a, sender, commands, enc);
    if (commands.empty()) {
      std::cerr << "engraver: nothing to resume: the controller says the job has finished\n";
      return;
    }
  }
  if (a.map.probe) {
    std::cerr << "engraver: probing the blank: the probe clip on the blank, the spindle off\n";
    const std::string path = a.map.height_map.empty()
                                 ? default_map_path(".", input_name(a.plan.file))
                                 : a.map.height_map;
    map = probe_for_job(sender, plan, a.map, a.plan.z_up_mm, path);
    refuse_job_leaving_map(plan, *map, path);
  }
  // The map goes first (a controller that restarted has lost it: a resume sends it again);
  // without one, a clear: no map of an earlier job compensates this one.
  const std::vector<QueuedCommand> frames = heightmap::job_map_commands(map ? &*map : nullptr);
  commands.insert(commands.begin(), frames.begin(), frames.end());
  std::cerr << fmt::format(
      "engraver: {} -> {}: {} curves, {} commands, {} bytes, job id {}; keys: h hold, "
      "r resume, x abort, +/- feed override\n",
      a.plan.file, link->name(), plan.curves.size(), commands.size(), wire_bytes(commands), job_id);
  JobOutcome outcome;
  {
    Keyboard keys(sender);
    ProgressMeter bar("send", "commands", std::cerr, ProgressMeter::for_stderr());
    bool told_zero = false;
    outcome = sender.run(commands, [&](const Progress& p) {
      if (p.status.state == proto::MachineState::kZeroing && !told_zero) {
        std::cerr << "engraver: zero the machine: jog to the corner with the joystick, then "
                     "press confirm\n";
        told_zero = true;
      }
      bar.update(p.executed, p.total, machine_detail(p));
    });
  }
  g_sender = nullptr;
  const SenderStats& st = sender.stats();
  std::cerr << fmt::format(
      "engraver: job {}: {} ({} frames, {} bytes, {} resent after busy or loss)\n",
      outcome_name(outcome), sender.message(), st.frames_sent, st.bytes_sent, st.retransmits);
  if (outcome != JobOutcome::kCompleted) {
    throw CommandFailure(exit_code(outcome), fmt::format("job {}", outcome_name(outcome)));
  }
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
  const JobPlan plan = load_plan(a.plan, &drawing);
  const std::string path =
      a.map.height_map.empty() ? default_map_path(".", input_name(a.plan.file)) : a.map.height_map;
  const LinkSpec spec = parse_link_spec(a.to);
  std::unique_ptr<Link> link = open_link(spec, std::chrono::milliseconds(5000));
  SenderOptions so;
  so.zero_first = !a.no_zero;
  Sender sender(*link, so);
  install_signals(&sender);
  sender.open_session();
  std::cerr << fmt::format(
      "engraver: probing the blank under {} through {}: the probe clip on the blank, the "
      "spindle off\n",
      a.plan.file, link->name());
  probe_for_job(sender, plan, a.map, a.plan.z_up_mm, path);
  g_sender = nullptr;
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
extern "C" void on_stop_sim(int) {
  g_stop_sim = true;
}

// --listen: ADDR:PORT, or serial:DEVICE (a tty or a pty's slave end), or a /dev path.
sim::ServerOptions listen_options(const std::string& listen) {
  sim::ServerOptions so;
  const std::string serial = "serial:";
  if (listen.compare(0, serial.size(), serial) == 0 || (!listen.empty() && listen[0] == '/')) {
    so.device = listen[0] == '/' ? listen : listen.substr(serial.size());
    so.device = so.device.substr(0, so.device.find(','));  // a baud rate means nothing here
    if (so.device.empty())
      throw CommandFailure(kExitUsage, fmt::format("--listen '{}': no device", listen));
    return so;
  }
  const size_t colon = listen.rfind(':');
  if (colon == std::string::npos) {
    throw CommandFailure(kExitUsage,
                         fmt::format("--listen '{}': expected ADDR:PORT or serial:DEVICE", listen));
  }
  so.address = listen.substr(0, colon);
  try {
    so.port = static_cast<uint16_t>(std::stoul(listen.substr(colon + 1)));
  } catch (const std::exception&) {
    throw CommandFailure(kExitUsage, fmt::format("--listen '{}': bad port", listen));
  }
  return so;
}

// --trace: one CSV line per executed tool position (machine time, machine frame).
class TraceWriter {
 public:
  explicit TraceWriter(const std::string& path) : out_(path, std::ios::trunc) {
    if (!out_) throw CommandFailure(kExitUsage, fmt::format("--trace '{}': cannot write", path));
    out_ << "t_ms,x_mm,y_mm,z_mm,pen,wall_ms\n";
  }
  // wall_ms: Unix time when the sample was simulated, to line up several machines' traces
  // (the machine clock may run up to the fast window ahead of it).
  void add(const sim::ToolSample& s) {
    const auto wall_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                             std::chrono::system_clock::now().time_since_epoch())
                             .count();
    out_ << fmt::format("{},{:.4f},{:.4f},{:.4f},{},{}\n", s.t_ms, s.x_mm, s.y_mm, s.z_mm,
                        s.z_mm < 0 ? 1 : 0, wall_ms);
  }
  bool ok() {
    out_.flush();
    return static_cast<bool>(out_);
  }

 private:
  std::ofstream out_;
};

void run_sim(const SimArgs& a) {
  sim::ServerOptions so = listen_options(a.listen);
  so.realtime = a.realtime;
  sim::SimOptions mo;
  mo.pause_confirm_ms = a.pause_confirm_ms;
  // The simulated blank over the work area (unless --surface gives its area).
  std::shared_ptr<heightmap::SimulatedBlank> blank;
  if (const std::optional<heightmap::SurfaceSpec> spec = surface_spec_of(a.surface)) {
    const config::MachineConfig& mc = mo.machine;
    blank = std::make_shared<heightmap::SimulatedBlank>(heightmap::SurfaceModel(
        *spec, heightmap::AreaMm{0, 0, mc.axis[config::kAxisX].travel_um / 1000.0,
                                 mc.axis[config::kAxisY].travel_um / 1000.0}));
    mo.surface_um = [blank](int32_t x_um, int32_t y_um) { return blank->surface_um(x_um, y_um); };
  }
  sim::SimMachine machine{mo};
  if (!machine.chip_ok()) std::cerr << "engraver: simulated TMC428 failed its self-check\n";
  std::unique_ptr<TraceWriter> trace;
  if (!a.trace.empty()) {
    trace = std::make_unique<TraceWriter>(a.trace);
    trace->add(machine.position());
  }
  if (trace || blank) {
    machine.set_sample_sink([&trace, blank](const sim::ToolSample& s) {
      if (blank) blank->tool_at(s.x_mm, s.y_mm, s.z_mm);
      if (trace) trace->add(s);
    });
  }
  std::unique_ptr<sim::SimServer> server;
  try {
    server = std::make_unique<sim::SimServer>(machine, so);
  } catch (const std::runtime_error& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
  struct sigaction sa {};
  sa.sa_handler = on_stop_sim;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  const std::string where = so.device.empty() ? fmt::format("{}:{}", so.address, server->port())
                                              : fmt::format("device {}", so.device);
  std::cerr << fmt::format(
      "engraver: simulated machine on {} ({}); Ctrl-C stops\n", where,
      a.realtime ? "real time" : "fast while the host talks, real time while it is silent");
  std::cerr << (a.pause_confirm_ms < 0
                    ? std::string("engraver: the simulated operator never confirms a pause\n")
                    : fmt::format("engraver: the simulated operator confirms each pause (#P) "
                                  "after {} ms\n",
                                  a.pause_confirm_ms));
  const uint64_t ms = server->run(g_stop_sim);
  machine.set_sample_sink(nullptr);
  if (trace && !trace->ok())
    std::cerr << fmt::format("engraver: --trace '{}': write failed\n", a.trace);
  std::cerr << fmt::format(
      "engraver: simulated {:.1f} s of machine time; {} pauses confirmed by the simulated "
      "operator; spindle {} ({} switchings)\n",
      ms / 1000.0, machine.pauses_confirmed(), machine.spindle_on() ? "on" : "off",
      machine.spindle_switches());
}

// ---- engraver run ----

struct RunArgs {
  PlanArgs plan;
  std::string outdir = "out";
  bool realtime = false;
  std::vector<double> blank_error;  // DX DY DEG: the flipped blank placed off by this much
  bool pins_only = false;           // with blank_error: no measured alignment
  std::string surface;              // --surface: the simulated blank
  HeightMapArgs map;
};

// A double-sided board's second setup, simulated: the blank on the pins off by an error, the
// simulated operator measuring the alignment holes (unless pins only), the job aligned to them.
struct FlipSimulation {
  pcb::RigidTransform error;      // nominal machine frame -> where the board really lies
  pcb::RigidTransform alignment;  // the job's measured placement (identity: pins only)
  std::vector<std::vector<Point2>> nominal_isolation_mm;  // the job as planned without error
  std::vector<double> measured_mm;
};

// Plans the nominal job, places the blank off by the error and, unless pins only, re-plans the
// job onto the holes as the simulated operator measures them (to the micrometre).
JobPlan plan_flip(const RunArgs& a, FlipSimulation* f) {
  Drawing drawing;
  JobPlan plan = load_plan(a.plan, &drawing);
  const std::vector<Point2> holes = board_alignment_holes_mm();
  if (holes.size() < 2)
    throw CommandFailure(kExitUsage,
                         "--blank-error simulates a double-sided board's second setup: give the "
                         "board job its --align-holes");
  if (!a.plan.board.align_measured_mm.empty())
    throw CommandFailure(kExitUsage,
                         "--blank-error measures the holes itself: leave out --align-measured");
  f->nominal_isolation_mm = board_isolation_paths_mm();
  f->error = pcb::placement_error((holes[0] + holes[1]) / 2, a.blank_error[0], a.blank_error[1],
                                  a.blank_error[2]);
  if (a.pins_only) return plan;
  PlanArgs aligned = a.plan;
  for (size_t i = 0; i < 2; ++i) {
    const Point2 m = f->error.apply(holes[i]);
    for (double v : {m.x(), m.y()})
      aligned.board.align_measured_mm.push_back(std::round(v * 1000) / 1000);
  }
  f->measured_mm = aligned.board.align_measured_mm;
  plan = load_plan(aligned, &drawing);
  f->alignment = board_placement();
  return plan;
}

// The points the firmware core generates for the job's curves (the same core, on the host),
// and the bytes the same path would take as G-code G1 lines at the same tolerance (for
// comparison); curve by curve, so nothing of the job's size is kept.
struct PointCount {
  size_t points = 0;
  size_t gcode_bytes = 0;
};

PointCount count_points(const JobPlan& plan, double tol_mm) {
  PointCount n;
  for (const PlannedCurve& c : plan.curves) {
    for (const Point2& p :
         firmware_points_mm(c.spline, static_cast<int>(std::lround(tol_mm * 1000)))) {
      ++n.points;
      n.gcode_bytes += fmt::formatted_size("G1 X{:.3f} Y{:.3f}\n", p.x(), p.y());
    }
  }
  return n;
}

// Half a pixel of the 1000-pixel plot of the job (zero corner to the far end of the curves).
double plot_step_mm(const JobPlan& plan) {
  const Extents& e = plan.extents_mm;
  if (e.empty()) return 0.05;
  const double span =
      std::max(e.max.x() - std::min(0.0, e.min.x()), e.max.y() - std::min(0.0, e.min.y()));
  return std::max(0.005, span / 2000.0);
}

void run_run(const RunArgs& a) {
  JobPlan plan;
  std::optional<FlipSimulation> flip;
  if (!a.blank_error.empty()) {
    flip.emplace();
    plan = plan_flip(a, &*flip);
  } else {
    Drawing drawing;  // only the plan is needed from here on
    plan = load_plan(a.plan, &drawing);
  }
  sim::SimJobOptions o;
  o.encode = encode_options(a.plan);
  o.realtime = a.realtime;
  // Polled as `send` polls the real machine (every 250 ms, here of machine time), so the
  // frames and bytes reported are those a real run would put on the wire.
  o.sender.status_interval = std::chrono::milliseconds(250);
  // The plot shows what its pixels can: keep a tool position every half pixel or so.
  o.trace_step_mm = plot_step_mm(plan);
  // The simulated blank (--surface) over the job unless its area is given, and the map the
  // controller follows (--height-map).
  const std::optional<heightmap::SurfaceSpec> surface_spec = surface_spec_of(a.surface);
  std::optional<heightmap::SurfaceModel> surface;
  if (surface_spec) {
    // The blank: from the zero corner to the job's far end and as far again as the margin.
    const Extents& e = plan.extents_mm;
    surface.emplace(*surface_spec,
                    e.empty() ? heightmap::AreaMm{0, 0, a.plan.work_mm[0], a.plan.work_mm[1]}
                              : heightmap::AreaMm{0, 0, e.max.x() + std::max(0.0, e.min.x()),
                                                  e.max.y() + std::max(0.0, e.min.y())});
  }
  std::optional<heightmap::HeightMap> map = load_height_map(a.map);
  if (map) refuse_job_leaving_map(plan, *map, a.map.height_map);
  if (a.map.probe && !surface)
    throw CommandFailure(kExitUsage,
                         "run --probe needs a simulated blank to touch: give --surface too");
  // The simulated probe touches the simulated blank.
  std::shared_ptr<heightmap::SimulatedBlank> blank;
  if (surface) {
    blank = std::make_shared<heightmap::SimulatedBlank>(*surface);
    o.machine.surface_um = [blank](int32_t x_um, int32_t y_um) {
      return blank->surface_um(x_um, y_um);
    };
  }
  // Measured from the job's first command on (not the probing's touches).
  bool job_started = !a.map.probe;
  // A board: the isolation cuts at full resolution, to check them against the copper (at
  // their planned height: the map's height taken off again), and their depth of cut
  // against the simulated blank.
  std::optional<sim::CutPathCollector> isolation_cuts;
  std::optional<heightmap::DepthMeter> depth;
  if (const std::optional<double> z = board_isolation_z_mm()) {
    isolation_cuts.emplace(*z, 0.002);
    if (surface) {
      heightmap::DepthOptions d;
      d.isolation_z_mm = *z;
      d.vbit_angle_deg = a.map.vbit_angle_deg;
      d.copper_um = a.map.copper_um;
      d.planned_width_um = a.plan.board.tool_width_mm * 1000.0;
      depth.emplace(*surface, map ? &*map : nullptr, d);  // --probe: set when probed
    }
  }
  o.on_sample = [&isolation_cuts, &depth, &map, &blank, &job_started](const sim::ToolSample& s) {
    if (blank) blank->tool_at(s.x_mm, s.y_mm, s.z_mm);
    if (!job_started || !isolation_cuts) return;
    sim::ToolSample planned = s;
    if (map) planned.z_mm -= map->interpolate_um(s.x_mm, s.y_mm) / 1000.0;
    isolation_cuts->add(planned);
    if (depth) depth->add(s.x_mm, s.y_mm, s.z_mm);
  };
  const std::string name = input_name(a.plan.file);
  std::filesystem::create_directories(a.outdir);
  const std::string base = (std::filesystem::path(a.outdir) / name).string();
  const std::string map_path =
      a.map.height_map.empty() ? default_map_path(a.outdir, name) : a.map.height_map;
  if (a.map.probe || map) {
    o.z_offset_mm = [&map](double x_mm, double y_mm) {
      return map ? map->interpolate_um(x_mm, y_mm) / 1000.0 : 0.0;
    };
  }
  // The job's map, or a clear without one, goes just before the job (as with send).
  o.before_job = [&](Sender& sender) {
    if (a.map.probe) {
      map = probe_for_job(sender, plan, a.map, a.plan.z_up_mm, map_path);
      refuse_job_leaving_map(plan, *map, map_path);
      if (depth) depth->set_applied_map(&*map);
    }
    job_started = true;
    return heightmap::job_map_commands(map ? &*map : nullptr);
  };
  const sim::SimJobResult r = [&] {
    ProgressMeter bar("run", "commands", std::cerr, ProgressMeter::for_stderr());
    o.on_progress = [&bar](Sender&, const Progress& p) {
      bar.update(p.executed, p.total, machine_detail(p));
    };
    return sim::run_sim_job(plan, o);
  }();

  // Plot: the drawing's curves against the simulated tool path.
  PlotInput plot = plot_input_from_plan(plan, name, 0.01, false);
  const std::vector<bool> pen_down = sim::pen_down_samples(r.trace, plan);
  for (size_t i = 0; i < r.trace.size(); ++i) {
    const sim::ToolSample& s = r.trace[i];
    const bool down = pen_down[i];
    if (plot.tool_path.empty() || plot.tool_path.back().pen_down != down) {
      ToolPathSegment seg;
      seg.pen_down = down;
      if (!plot.tool_path.empty()) seg.points_mm.push_back(plot.tool_path.back().points_mm.back());
      plot.tool_path.push_back(seg);
    }
    plot.tool_path.back().points_mm.push_back(Point2(s.x_mm, s.y_mm));
  }
  write_plot(plot, base + ".svg", base + ".png");
  write_board_plot_if_planned(base, plot.tool_path);  // copper, isolation width, holes

  const double feed = a.plan.feed_mm_s;
  const double ideal_s = plan.cut_length_mm / feed;
  std::optional<SimulatedIsolation> iso;
  std::optional<Registration> registration;
  if (isolation_cuts && flip) {
    // Where the cuts land on the board: back through the placement error; then into the
    // frame the job was planned in, for the check against its copper.
    registration =
        registration_error(isolation_cuts->paths(), flip->error, flip->nominal_isolation_mm);
    const pcb::RigidTransform back = flip->error.inverse();
    std::vector<std::vector<Point2>> on_copper = isolation_cuts->paths();
    for (std::vector<Point2>& path : on_copper)
      for (Point2& p : path) p = flip->alignment.apply(back.apply(p));
    iso = check_simulated_isolation(on_copper, isolation_cuts->samples());
  } else if (isolation_cuts) {
    iso = check_simulated_isolation(isolation_cuts->paths(), isolation_cuts->samples());
  }
  nlohmann::json j;
  j["drawing"] = a.plan.file;
  j["outcome"] = outcome_name(r.outcome);
  j["message"] = r.message;
  j["curves"] = plan.curves.size();
  j["pen_lifts"] = plan.pen_lifts;
  j["commands"] = r.commands;
  j["frames_sent"] = r.stats.frames_sent;
  j["bytes_sent"] = r.stats.bytes_sent;
  j["job_wire_bytes"] = r.wire_bytes;
  j["job_id"] = r.job_id;
  const PointCount points = count_points(plan, a.plan.tol_mm);
  j["gcode_g1_bytes_same_tolerance"] = points.gcode_bytes;
  j["retransmits"] = r.stats.retransmits;
  j["status_queries"] = r.stats.status_queries;
  j["points_generated"] = points.points;
  j["planned_cut_mm"] = plan.cut_length_mm;
  j["planned_rapid_mm"] = plan.rapid_length_mm;
  j["traced_cut_mm"] = r.cut_mm;
  j["traced_rapid_mm"] = r.rapid_mm;
  j["feed_mm_per_s"] = feed;
  j["chord_tolerance_mm"] = a.plan.tol_mm;
  j["simulated_job_s"] = r.motion_s;
  j["simulated_cut_s"] = r.cut_s;
  j["cut_length_over_feed_s"] = ideal_s;
  j["max_contour_error_um"] = r.max_contour_error_um;
  j["max_contour_error_at_mm"] = {r.worst_contour_sample.x_mm, r.worst_contour_sample.y_mm};
  std::optional<heightmap::DepthReport> depth_report;
  if (depth) {
    depth_report = depth->report();
    j["surface"] = heightmap::surface_spec_text(surface->spec());
    j["depth_of_cut"] = depth_report_json(*depth_report, map.has_value());
    write_depth_error_svg(depth_report->kept, 50.0, name, base + ".depth.svg");
  }
  if (map) {
    j["height_map"] = {{"file", a.map.probe ? map_path : a.map.height_map},
                       {"rows", map->rows},
                       {"cols", map->cols},
                       {"min_um", map->min_um()},
                       {"max_um", map->max_um()},
                       {"frames", r.setup_commands},
                       {"wire_bytes", r.setup_wire_bytes}};
    if (!a.map.probe) write_height_map_svg(*map, name, map_picture_path(base + ".map.json"));
  }
  if (iso) {
    j["simulated_isolation_check"] = {
        {"tolerance_mm", iso->tolerance_mm},
        {"paths", iso->paths},
        {"samples", iso->samples},
        {"islands", iso->check.islands},
        {"copper_hits", iso->check.hits.size()},
        {"unseparated_pairs", iso->check.unseparated.size()},
        {"min_clearance_um", iso->min_clearance_um},
        {"planned_min_clearance_um", iso->planned_min_clearance_um},
        {"min_clearance_at_mm", {iso->min_clearance_at_mm.x(), iso->min_clearance_at_mm.y()}}};
    if (!std::isnan(iso->clearing_min_clearance_um))
      j["simulated_isolation_check"]["clearing_tool_min_clearance_um"] =
          iso->clearing_min_clearance_um;
  }
  if (flip) {
    j["flip"] = {{"blank_error",
                  {{"dx_mm", a.blank_error[0]},
                   {"dy_mm", a.blank_error[1]},
                   {"rotation_deg", a.blank_error[2]}}},
                 {"measured_holes_mm", flip->measured_mm},
                 {"aligned", !a.pins_only},
                 {"alignment",
                  {{"rotation_deg", flip->alignment.rotation_rad * 180 / M_PI},
                   {"shift_mm", {flip->alignment.shift_mm.x(), flip->alignment.shift_mm.y()}}}}};
    if (registration)
      j["registration_error"] = {{"max_um", registration->max_um},
                                 {"mean_um", registration->mean_um},
                                 {"samples", registration->samples}};
  }
  j["plot_tool_path"] = {{"samples_kept", r.trace.size()},
                         {"samples_simulated", r.trace_samples},
                         {"step_mm", r.trace_step_mm}};
  j["simulated_machine_ms"] = r.virtual_ms;
  j["wall_s"] = r.wall_s;
  j["speedup_vs_real_time"] = r.wall_s > 0 ? r.virtual_ms / 1000.0 / r.wall_s : 0.0;
  j["simulator_cpu_s"] = r.cpu_s;
  j["speedup_per_cpu_second"] = r.cpu_s > 0 ? r.virtual_ms / 1000.0 / r.cpu_s : 0.0;
  j["lcd"] = {r.lcd[0], r.lcd[1]};
  j["pauses_confirmed_by_simulated_operator"] = r.pauses_confirmed;
  j["pause_confirm_ms"] = o.machine.pause_confirm_ms;
  j["spindle_on_at_end"] = r.spindle_on;
  {
    std::ofstream out(base + ".json");
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  }
  std::cout << fmt::format(
      "{}: {} curves, {} pen lifts; job {}\n"
      "  sent {} commands in {} frames, {} bytes ({} resent after busy or loss); the job as "
      "frames: {} bytes, "
      "as G-code G1 at the same tolerance: {} bytes\n"
      "  tool path {:.1f} mm cut + {:.1f} mm rapid; simulated job time {:.1f} s, of which "
      "cutting {:.1f} s (cut length / feed {:.1f} s)\n"
      "  max contour error {:.1f} um at ({:.3f}, {:.3f}) mm; simulated {:.1f} s of machine "
      "time in {:.2f} s "
      "({:.2f} s of processor time: {:.0f}x real time)\n"
      "  {} pauses confirmed by the simulated operator ({} ms after each); spindle {} at the "
      "end\n"
      "  plot: {}.svg, {}.png; report: {}.json\n",
      a.plan.file, plan.curves.size(), plan.pen_lifts, outcome_name(r.outcome), r.commands,
      r.stats.frames_sent, r.stats.bytes_sent, r.stats.retransmits, r.wire_bytes,
      j["gcode_g1_bytes_same_tolerance"].get<size_t>(), r.cut_mm, r.rapid_mm, r.motion_s, r.cut_s,
      ideal_s, r.max_contour_error_um, r.worst_contour_sample.x_mm, r.worst_contour_sample.y_mm,
      r.virtual_ms / 1000.0, r.wall_s, r.cpu_s, j["speedup_per_cpu_second"].get<double>(),
      r.pauses_confirmed, o.machine.pause_confirm_ms, r.spindle_on ? "on" : "off", base, base,
      base);
  if (r.trace_step_mm > o.trace_step_mm)
    std::cout << fmt::format(
        "  the plot's tool path is thinned to {:.3f} mm steps ({} of {} samples kept, a long "
        "job)\n",
        r.trace_step_mm, r.trace.size(), r.trace_samples);
  if (iso) {
    std::cout << fmt::format(
        "  simulated isolation cuts ({} paths, {} samples) against the copper: {} copper hits "
        "beyond {:.3f} mm, {} unseparated pairs; least clearance of the tool's edge {:.1f} um "
        "at ({:.3f}, {:.3f}) mm (planned paths: {:.1f} um)\n",
        iso->paths, iso->samples, iso->check.hits.size(), iso->tolerance_mm,
        iso->check.unseparated.size(), iso->min_clearance_um, iso->min_clearance_at_mm.x(),
        iso->min_clearance_at_mm.y(), iso->planned_min_clearance_um);
  }
  if (registration) {
    std::cout << fmt::format(
        "  double-sided: blank placed off by ({:.3f}, {:.3f}) mm and {:.2f} deg; {}; the cuts "
        "land {:.1f} um (max, mean {:.1f} um) from where they belong on the board\n",
        a.blank_error[0], a.blank_error[1], a.blank_error[2],
        a.pins_only ? "pins only, no measured alignment" : "the job aligned to the measured holes",
        registration->max_um, registration->mean_um);
  }
  if (depth_report) {
    std::cout << depth_report_text(*depth_report, map.has_value());
    std::cout << fmt::format("  depth error plot: {}.depth.svg\n", base);
  }
  if (r.outcome != JobOutcome::kCompleted) {
    throw CommandFailure(exit_code(r.outcome),
                         fmt::format("job {}: {}", outcome_name(r.outcome), r.message));
  }
  if (iso) {
    // The simulated machine cut copper: the real one would too.
    try {
      pcb::refuse_copper_hits(iso->check, "the simulated tool path");
    } catch (const pcb::CopperCutError& e) {
      throw CommandFailure(kExitCutsCopper, name + ": " + e.what());
    }
  }
}

void add_machine_commands(CLI::App& app) {
  auto send_args = std::make_shared<SendArgs>();
  CLI::App* send = app.add_subcommand("send", "plan a drawing and stream it to the machine");
  add_plan_options(send, &send_args->plan);
  add_height_map_options(send, &send_args->map, HeightMapCommand::kSend);
  send->add_option("--to", send_args->to,
                   "tcp://HOST:PORT (XPort, default port 10001) or serial:DEVICE[,BAUD]")
      ->required();
  send->add_flag("--no-zero", send_args->no_zero, "do not start manual zeroing if not zeroed");
  send->add_option("--poll-ms", send_args->poll_ms,
                   "status poll interval (keep-alive); 0 = one query always in flight")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  send->add_flag("--resume", send_args->resume,
                 "continue the job from where the controller says it stopped (lost link, abort, "
                 "alarm); give the same file and plan options as the first send");
  send->add_option("--resume-at", send_args->resume_at,
                   "INDEX[:POINT]: continue from job command INDEX (curve point POINT), e.g. "
                   "after a controller restart, from the last progress line's 'job' figures")
      ->excludes("--resume");
  send->footer(
      "Example: engraver send board.dxf --to tcp://192.168.1.50:10001 --feed 8\n"
      "After a lost link: engraver send board.dxf --to ... --feed 8 --resume\n"
      "Keys: h hold, r resume, x abort, +/- feed override. Signals: INT/TERM abort, USR1 hold, "
      "USR2 resume.\nExit: 0 done, 1 job refused, 2 bad input, 3 aborted, 4 alarm, "
      "5 command refused by the controller, 6 link lost, 7 stalled (no progress for 30 s), 8 a "
      "board job that would cut copper (refused before streaming).");
  send->callback([send_args] {
    try {
      run_send(*send_args);
    } catch (const LinkError& e) {
      throw CommandFailure(kExitLinkLost, e.what());
    }
  });

  auto probe_args = std::make_shared<ProbeArgs>();
  CLI::App* probe =
      app.add_subcommand("probe", "probe the blank on a grid over a job and write its height map");
  add_plan_options(probe, &probe_args->plan);
  add_height_map_options(probe, &probe_args->map, HeightMapCommand::kProbe);
  probe
      ->add_option("--to", probe_args->to,
                   "tcp://HOST:PORT (XPort, default port 10001) or serial:DEVICE[,BAUD]")
      ->required();
  probe->add_flag("--no-zero", probe_args->no_zero, "do not start manual zeroing if not zeroed");
  probe->footer(
      "Example: engraver probe board/ --to tcp://192.168.1.50:10001 --height-map board.map.json\n"
      "then: engraver send board/ --to ... --height-map board.map.json\n"
      "Exit: 0 map written, 1 probing refused (a point disagreeing with its neighbours, two "
      "touches apart, heights spanning more than 1 mm), 2 bad input or options, 5 the "
      "controller refused the probe (no contact, spindle on, probe closed), 6 link lost.");
  probe->callback([probe_args] {
    try {
      run_probe(*probe_args);
    } catch (const LinkError& e) {
      throw CommandFailure(kExitLinkLost, e.what());
    }
  });

  auto sim_args = std::make_shared<SimArgs>();
  CLI::App* sim = app.add_subcommand("sim", "run the simulated machine on a TCP port");
  sim->add_option("--listen", sim_args->listen,
                  "ADDR:PORT (loopback by default), or serial:DEVICE (a tty or a pty)")
      ->capture_default_str();
  sim->add_flag("--realtime", sim_args->realtime, "machine time always follows the wall clock");
  sim->add_option("--trace", sim_args->trace,
                  "write the executed tool positions as CSV: t_ms,x_mm,y_mm,z_mm,pen,wall_ms");
  add_surface_option(sim, &sim_args->surface);
  sim->add_option("--pause-confirm-ms", sim_args->pause_confirm_ms,
                  "the simulated operator confirms a pause (#P) after this long; -1 never")
      ->capture_default_str();
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

  auto run_args = std::make_shared<RunArgs>();
  CLI::App* run = app.add_subcommand(
      "run",
      "the main job: simulate the machine and send the drawing to it (in lockstep, one "
      "process)");
  add_plan_options(run, &run_args->plan);
  run->add_option("-o,--outdir", run_args->outdir, "where NAME.svg/.png/.json go")
      ->capture_default_str();
  run->add_flag("--realtime", run_args->realtime, "simulate in real time");
  run->add_option("--blank-error", run_args->blank_error,
                  "double-sided, second setup: DX DY DEG, the simulated machine's flipped blank "
                  "sits this far off on its pins (mm, mm, degrees about the holes' middle); the "
                  "simulated operator measures the alignment holes and the job is aligned to "
                  "them; the report gives the registration error")
      ->expected(3);
  run->add_flag("--pins-only", run_args->pins_only,
                "with --blank-error: no measured alignment (the pins alone)");
  add_surface_option(run, &run_args->surface);
  add_height_map_options(run, &run_args->map, HeightMapCommand::kRun);
  run->footer(
      "Example: engraver run samples/engraver-word.dxf -o out\n"
      "Progress on stderr (a bar on a terminal, a line every 5 s otherwise).\n"
      "Exit: 0 done, 1 job refused, 2 bad input, 3 aborted, 4 alarm, 5 command refused by "
      "the controller, 6 link lost, 7 stalled (no progress for 30 s of machine time), 8 a board "
      "job whose controller points or simulated path cut copper.");
  run->callback([run_args] {
    try {
      run_run(*run_args);
    } catch (const LinkError& e) {
      throw CommandFailure(kExitLinkLost, e.what());
    }
  });
}

const CommandRegistrar registrar("machine", add_machine_commands);

}  // namespace

}  // namespace host::cli
