// `engraver board` as a function (see board_command.h).
#include "host/lib/commands/board_command.h"

#include <fmt/format.h>    // fmt::format
#include <sys/resource.h>  // getrusage: peak memory

#include <chrono>      // steady_clock
#include <cmath>       // M_PI
#include <ctime>       // std::clock
#include <filesystem>  // create_directories
#include <fstream>     // std::ofstream

#include "host/lib/commands/exit_codes.h"  // CommandFailure
#include "host/lib/pcb/board_check.h"
#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/counted.h"          // counted: "1 hole", "2 holes"
#include "host/lib/plan/firmware_spline.h"  // sample
#include "host/lib/plot/board_plot.h"
#include "host/lib/stream/job_encoder.h"

namespace host::commands {

nlohmann::json narrow_gaps_json(const std::vector<pcb::NarrowGap>& gaps) {
  nlohmann::json j = nlohmann::json::array();
  for (const pcb::NarrowGap& g : gaps) {
    j.push_back({{"x_mm", g.at.x / pcb::kNmPerMm},
                 {"y_mm", g.at.y / pcb::kNmPerMm},
                 {"gap_mm", g.gap_mm},
                 {"islands", {g.island_a, g.island_b}}});
  }
  return j;
}

namespace {

using pcb::LayerKind;

std::string g1(const Point2& p) {
  return fmt::format("G1 X{:.3f} Y{:.3f}\n", p.x(), p.y());
}

double peak_memory_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

nlohmann::json plan_report_json(const pcb::BoardJob& job, const pcb::BoardOptions& o) {
  const pcb::BoardReport& r = job.report;
  nlohmann::json j;
  j["side"] = o.side == pcb::BoardSide::kBottom ? "bottom" : "top";
  j["first_tool"] = r.first_tool;
  j["islands"] = r.islands;
  j["narrow_gaps"] = narrow_gaps_json(r.narrow_gaps);
  j["isolation_contours"] = r.isolation_contours;
  j["isolation_length_mm"] = r.isolation_length_mm;
  j["isolation_vertices"] = r.isolation_vertices;
  j["fit"] = {{"lines", r.fit.lines}, {"arcs", r.fit.arcs}, {"cubics", r.fit.cubics}};
  j["holes"] = r.holes;
  j["board_holes"] = r.board_holes;
  j["holes_on_copper"] = r.holes_on_copper;
  j["slots"] = r.slots;
  j["drill_tools"] = r.drill_tools;
  j["drill_travel_file_order_mm"] = r.drill_travel_file_order_mm;
  j["drill_travel_ordered_mm"] = r.drill_travel_ordered_mm;
  j["tabs"] = r.tabs;
  j["cutout_length_mm"] = r.cutout_length_mm;
  j["no_cutout"] = r.no_cutout;  // why there is none ("" when the job cuts the board out)
  j["tool_changes"] = r.tool_changes;
  j["notes"] = r.notes;
  j["steps"] = job.plan.steps.size();
  j["cut_length_mm"] = job.plan.cut_length_mm;
  j["rapid_length_mm"] = job.plan.rapid_length_mm;
  j["extents_mm"] = {{"min", {job.plan.extents_mm.min.x(), job.plan.extents_mm.min.y()}},
                     {"max", {job.plan.extents_mm.max.x(), job.plan.extents_mm.max.y()}}};
  return j;
}

// The name of a board given as named files (no folder): the first option's file's.
std::string named_files_board_name(const BoardCommandOptions& a) {
  for (const std::string& f : {a.top, a.bottom, a.outline})
    if (!f.empty()) return board_name(f);
  return a.drills.empty() ? std::string() : board_name(a.drills.front());
}

}  // namespace

WireMeasure measure_wire(const pcb::BoardJob& job, double tol_mm) {
  WireMeasure m;
  JobPlan iso;
  for (const PlanStep& s : job.plan.steps) {
    if (s.kind == PlanStep::kSpline && s.curve >= 0 &&
        static_cast<size_t>(s.curve) < job.isolation_curves)
      iso.steps.push_back(s);
  }
  EncodeOptions eo;
  eo.title.clear();
  for (const QueuedCommand& c : encode_job(iso, eo)) {
    if (c.step < 0) continue;  // set-up frames
    ++m.spline_frames;
    m.spline_bytes += frame_bytes(c);
  }
  eo.splines = SplineFrames::kCompact;
  for (const QueuedCommand& c : encode_job(iso, eo)) {
    if (c.step >= 0) m.spline_bytes_compact += frame_bytes(c);
  }
  eo.splines = SplineFrames::kFixed;
  for (const QueuedCommand& c : encode_job(iso, eo)) {
    if (c.step >= 0) m.spline_bytes_full += frame_bytes(c);
  }
  for (size_t i = 0; i < job.isolation_curves; ++i) {
    const std::vector<Point2> pts = sample(job.plan.curves[i].spline(), tol_mm);
    for (size_t k = 1; k < pts.size(); ++k) {
      ++m.g1_lines;
      m.g1_bytes += g1(pts[k]).size();
    }
  }
  // Clipper's vertices (what a G-code CAM writes from the same polygons).
  m.g1_vertex_bytes = job.report.isolation_vertices * g1(Point2(123.456, 78.901)).size();
  return m;
}

std::vector<size_t> bytes_per_tool(const pcb::BoardJob& job) {
  std::vector<size_t> tool_of_step(job.plan.steps.size(), 0);
  size_t tool = 0;
  for (size_t i = 0; i < job.plan.steps.size(); ++i) {
    if (job.plan.steps[i].kind == PlanStep::kPause) ++tool;
    tool_of_step[i] = tool;
  }
  std::vector<size_t> bytes(std::max<size_t>(job.tools.size(), tool + 1), 0);
  EncodeOptions eo;
  eo.title.clear();
  for (const QueuedCommand& c : encode_job(job.plan, eo))
    if (c.step >= 0) bytes[tool_of_step[static_cast<size_t>(c.step)]] += frame_bytes(c);
  return bytes;
}

BoardFiles read_board_command_files(const BoardCommandOptions& a, const CommandLog& log) {
  BoardFiles b;
  for (const std::string& f : a.files) {
    BoardFiles one = read_board_input(f, a.board.side);
    for (auto* kind : {&one.layers.copper_top, &one.layers.copper_bottom, &one.layers.drill,
                       &one.layers.outline})
      for (pcb::PcbLayer& l : *kind) b.layers.add(std::move(l));
    b.notes.insert(b.notes.end(), one.notes.begin(), one.notes.end());
    b.warnings.insert(b.warnings.end(), one.warnings.begin(), one.warnings.end());
    if (b.name.empty()) {
      b.name = one.name;
      b.from_directory = one.from_directory;
    }
    if (b.side.empty()) b.side = one.side;
  }
  // A layer named by its option is that kind, whatever its name or attributes say.
  if (!a.top.empty()) add_named_layer(&b, a.top, LayerKind::kCopperTop);
  if (!a.bottom.empty()) add_named_layer(&b, a.bottom, LayerKind::kCopperBottom);
  if (!a.outline.empty()) add_named_layer(&b, a.outline, LayerKind::kOutline);
  for (const std::string& d : a.drills) add_named_layer(&b, d, LayerKind::kDrill);
  if (b.name.empty()) b.name = named_files_board_name(a);
  // A bottom-side job of named files is named after its bottom copper (it took the first
  // file's name, often the top's); a folder keeps the folder's.
  const std::string side = !a.board.side.empty() ? a.board.side : b.side;
  const bool bottom = side == "bottom" || (side.empty() && b.layers.copper_top.empty() &&
                                           !b.layers.copper_bottom.empty());
  if (bottom && !b.from_directory && !b.layers.copper_bottom.empty())
    b.name = board_name(b.layers.copper_bottom.front().path);
  log_board_notes(b, log);
  return b;
}

BoardResult plan_board_command(const BoardCommandOptions& a, const CommandLog& log) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  const BoardFiles b = read_board_command_files(a, log);
  BoardResult r;
  r.name = b.name;
  r.options = board_options_for(a.board, a.machine, b);
  r.job = plan_board_files(b, r.options, a.board.alignment.measured_mm);
  for (const std::string& n : r.job.report.notes) log("note: " + n);
  r.plan_cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.plan_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.plan_peak_mb = peak_memory_mb();
  return r;
}

void check_board(const BoardCommandOptions& a, BoardResult* r, const CommandLog& log) {
  if (a.wire_bytes) r->wire = measure_wire(r->job, a.tol_mm);
  r->tool_bytes = bytes_per_tool(r->job);
  if (!a.check || r->job.copper_machine.empty()) return;
  const pcb::IsolationCheck c = pcb::check_planned_isolation(r->job, r->options);
  r->check_ok = c.hits.empty() && c.unseparated.size() <= r->job.report.narrow_gaps.size();
  if (!c.ok() && c.hits.empty()) log("isolation check: " + pcb::describe(c));
  r->check = c;
}

nlohmann::json board_report_json(const BoardCommandOptions& a, const BoardResult& r) {
  const pcb::BoardJob& job = r.job;
  nlohmann::json j = plan_report_json(job, r.options);
  j["board"] = r.name;
  j["files_to_plan_cpu_s"] = r.plan_cpu_s;
  j["files_to_plan_wall_s"] = r.plan_wall_s;
  j["files_to_plan_peak_mb"] = r.plan_peak_mb;
  if (r.wire) {
    const WireMeasure& w = *r.wire;
    j["isolation_spline_frames"] = w.spline_frames;
    j["isolation_spline_bytes"] = w.spline_bytes;
    j["isolation_spline_bytes_compact"] = w.spline_bytes_compact;
    j["isolation_spline_bytes_fixed_width"] = w.spline_bytes_full;
    j["isolation_g1_lines_same_tolerance"] = w.g1_lines;
    j["isolation_g1_bytes_same_tolerance"] = w.g1_bytes;
    j["isolation_g1_bytes_every_vertex"] = w.g1_vertex_bytes;
    j["chord_tolerance_mm"] = a.tol_mm;
  }
  if (!job.alignment_holes_mm.empty()) {
    // Where the pins stand (machine frame), hole 1 first: what the operator measures.
    nlohmann::json holes = nlohmann::json::array();
    for (const Point2& h : job.alignment_holes_mm) holes.push_back({h.x(), h.y()});
    j["alignment"] = {
        {"holes_mm", holes},
        {"flip_axis_machine_x_mm", job.alignment_holes_mm.front().x()},
        {"flip_axis_file_x_mm", job.flip_axis_file_x_mm},
        {"placement",
         {{"rotation_deg", job.frame.placement.rotation_rad * 180 / M_PI},
          {"shift_mm", {job.frame.placement.shift_mm.x(), job.frame.placement.shift_mm.y()}}}}};
  }
  j["bytes_per_tool"] = nlohmann::json::array();
  for (size_t t = 0; t < job.tools.size(); ++t) {
    j["bytes_per_tool"].push_back({{"tool", t + 1},
                                   {"name", job.tools[t].label},
                                   {"diameter_mm", job.tools[t].diameter_mm},
                                   {"bytes", r.tool_bytes[t]}});
  }
  if (r.check) {
    j["check"] = {{"passed", r.check_ok},
                  {"tolerance_mm", pcb::isolation_check_tolerance_mm(r.options)},
                  {"islands", r.check->islands},
                  {"copper_hits", r.check->hits.size()},
                  {"unseparated_pairs", r.check->unseparated.size()}};
  }
  return j;
}

namespace {

// The drilling line: what this job drills, and how many of the drill files' holes sit in this
// side's copper pads (the alignment check of drill file and copper). A bottom side after a
// top side with alignment holes drills nothing: the top side drilled every hole.
std::string drilling_text(const pcb::BoardReport& p, size_t alignment_holes) {
  const std::string in_pads = p.board_holes
                                  ? fmt::format("{} of the board's {} in this side's copper pads",
                                                p.holes_on_copper, counted(p.board_holes, "hole"))
                                  : std::string("no drill file");
  if (p.holes == 0 && (p.board_holes > 0 || alignment_holes > 0))
    return fmt::format(
        "none on this side: the top side's job drills the holes ({}{})",
        alignment_holes ? counted(alignment_holes, "alignment hole") + "; " : std::string(),
        in_pads);
  const size_t pins = p.holes > p.board_holes ? p.holes - p.board_holes : 0;
  return fmt::format("{} ({}{}), {}, {}; travel {:.1f} mm (file order {:.1f} mm)",
                     counted(p.holes, "hole"), in_pads,
                     pins ? "; " + counted(pins, "alignment hole") : std::string(),
                     counted(p.slots, "slot"), counted(p.drill_tools, "size"),
                     p.drill_travel_ordered_mm, p.drill_travel_file_order_mm);
}

}  // namespace

std::string board_report_text(const BoardCommandOptions& a, const BoardResult& r) {
  const pcb::BoardReport& p = r.job.report;
  const std::string side = r.options.side == pcb::BoardSide::kBottom ? "bottom" : "top";
  std::string tool_bytes;
  for (size_t t = 0; t < r.job.tools.size(); ++t)
    tool_bytes += fmt::format("{}{} {} B", t ? ", " : "", r.job.tools[t].label, r.tool_bytes[t]);
  std::string s = fmt::format(
      "{}: {} side, first tool {}\n"
      "  isolation: {}, {}, {:.1f} mm ({}, {}, {}); {}\n",
      r.name, side, p.first_tool, counted(p.islands, "island"),
      counted(p.isolation_contours, "contour"), p.isolation_length_mm, counted(p.fit.lines, "line"),
      counted(p.fit.arcs, "arc"), counted(p.fit.cubics, "cubic"),
      counted(p.narrow_gaps.size(), "narrow gap"));
  if (r.wire) {
    const WireMeasure& w = *r.wire;
    s += fmt::format(
        "  as splines {} bytes in {} frames ({} as #K, {} as #D); as G1 at {} mm: {} "
        "bytes ({:.1f}x); G1 through every vertex: {} bytes\n",
        w.spline_bytes, w.spline_frames, w.spline_bytes_compact, w.spline_bytes_full, a.tol_mm,
        w.g1_bytes,
        w.spline_bytes ? static_cast<double>(w.g1_bytes) / static_cast<double>(w.spline_bytes)
                       : 0.0,
        w.g1_vertex_bytes);
  }
  s += "  drilling: " + drilling_text(p, r.job.alignment_holes_mm.size()) + "\n";
  const std::string cutout = p.no_cutout.empty()
                                 ? fmt::format("cut-out: {:.1f} mm per pass, {}",
                                               p.cutout_length_mm, counted(p.tabs, "tab"))
                                 : "no cut-out: " + p.no_cutout;
  s += fmt::format(
      "  {}; {}\n"
      "  bytes per tool: {}\n"
      "  files -> plan: {:.3f} s CPU, peak {:.1f} MB\n",
      cutout, counted(p.tool_changes, "tool change"), tool_bytes, r.plan_cpu_s, r.plan_peak_mb);
  // The check's outcome, passed too: a summary without it read the same as one with none.
  if (r.check && r.check->ok()) {
    s += fmt::format("  check: passed: no copper cut, {} each cut free (to {:.3f} mm)\n",
                     counted(r.check->islands, "island"),
                     pcb::isolation_check_tolerance_mm(r.options));
  } else if (r.check && r.check_ok) {  // joined only across the narrow gaps allowed
    s += fmt::format(
        "  check: passed: no copper cut; {} of islands not separated, across the {} allowed "
        "(--allow-narrow-gaps)\n",
        counted(r.check->unseparated.size(), "pair"), counted(p.narrow_gaps.size(), "narrow gap"));
  } else if (r.check) {
    s += fmt::format("  check: failed: {}, {} of islands not separated\n",
                     counted(r.check->hits.size(), "copper hit"),
                     counted(r.check->unseparated.size(), "pair"));
  } else if (!a.check) {
    s += "  check: skipped (--no-check)\n";
  }
  for (const pcb::NarrowGap& g : p.narrow_gaps)
    s += "  " + pcb::describe_gap(g, r.options.isolation) + "\n";
  for (size_t i = 0; i < r.job.alignment_holes_mm.size(); ++i)
    s += fmt::format("  alignment hole {} at ({:.3f}, {:.3f}) mm\n", i + 1,
                     r.job.alignment_holes_mm[i].x(), r.job.alignment_holes_mm[i].y());
  if (a.plot) s += "  plot: " + r.base + ".board.svg" + (a.png ? ", .png; " : "; ");
  s += "report: " + r.base + ".board.json\n";
  return s;
}

void write_board_outputs(const BoardCommandOptions& a, const nlohmann::json& report,
                         BoardResult* r) {
  std::filesystem::create_directories(a.outdir);
  r->base = (std::filesystem::path(a.outdir) / r->name).string();
  if (a.plot) {
    BoardPlotInput in;
    in.title = fmt::format("{} ({} side)", r->name, report["side"].get<std::string>());
    in.job = &r->job;
    write_board_plot(in, r->base + ".board.svg", a.png ? r->base + ".board.png" : "");
  }
  std::ofstream out(r->base + ".board.json");
  out << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

void refuse_failed_board(const BoardResult& r) {
  if (!r.check) return;
  try {
    pcb::refuse_copper_hits(*r.check, "the planned isolation paths");
  } catch (const pcb::CopperCutError& e) {
    throw CommandFailure(kExitCutsCopper, e.what());
  }
  if (!r.check_ok) throw CommandFailure(kExitJobFailed, "the isolation check failed (see above)");
}

BoardResult run_board(const BoardCommandOptions& o, const CommandLog& log) {
  BoardResult r = plan_board_command(o, log);
  check_board(o, &r, log);
  return r;
}

}  // namespace host::commands
