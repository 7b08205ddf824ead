// `engraver board` and the PCB hooks of `points`, `run` and `send` (see board_cli.h).
#include "host/cli/board_cli.h"

#include <fmt/format.h>       // fmt::format
#include <sys/resource.h>     // getrusage: peak memory
#include <nlohmann/json.hpp>  // nlohmann::json

#include <algorithm>   // std::sort
#include <chrono>      // steady_clock
#include <cmath>       // std::lround, M_PI
#include <ctime>       // std::clock
#include <filesystem>  // directories
#include <fstream>     // std::ofstream
#include <iomanip>     // std::setprecision
#include <iostream>    // std::cout, std::cerr
#include <limits>      // std::numeric_limits
#include <sstream>     // std::istringstream

#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/cli/terminal_text.h"
#include "host/lib/pcb/board_check.h"
#include "host/lib/pcb/board_files.h"  // BoardFileSet, read_board_file
#include "host/lib/pcb/isolation_check.h"
#include "host/lib/pcb/pcb_file_names.h"
#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plan/firmware_points.h"
#include "host/lib/plan/firmware_spline.h"
#include "host/lib/plot/board_plot.h"
#include "host/lib/stream/job_encoder.h"

namespace host::cli {

namespace {

using pcb::LayerKind;
using pcb::PcbLayer;

// ---- Reading a board's files ----

struct BoardFiles {
  pcb::BoardFileSet layers;  // by kind, as the server's board jobs hold them
  std::string name;          // for output files and the job title
  std::string side;          // from a "top:" / "bottom:" prefix
  std::vector<std::string> notes;
  std::vector<std::string> warnings;  // the readers' (a parameter ignored, a tool left out)
  bool from_directory = false;        // the name is the folder's
};

// Everything said about a board's files, on stderr.
void print_notes(const BoardFiles& b) {
  for (const std::string& n : b.notes) std::cerr << "engraver: note: " << printable(n) << "\n";
  for (const std::string& w : b.warnings)
    std::cerr << "engraver: warning: " << printable(w) << "\n";
}

PcbLayer read_layer(const std::string& path, LayerKind forced) {
  try {
    return pcb::read_board_file(path, forced);
  } catch (const pcb::PcbReadError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

// The reader's warnings about a layer (its other notes are for `engraver info`).
const PcbLayer& take_warnings(BoardFiles* b, const PcbLayer& l) {
  const std::string warning = "warning: ";
  for (const std::string& n : l.notes) {
    const size_t at = n.find(warning);
    if (at != std::string::npos)
      b->warnings.push_back(l.path + ": " + n.substr(0, at) + n.substr(at + warning.size()));
  }
  return l;
}

void add_layer(BoardFiles* b, PcbLayer l, bool from_directory) {
  const std::string path = l.path;
  take_warnings(b, l);
  if (b->layers.add(std::move(l))) return;
  if (from_directory) {
    b->notes.push_back(path + ": not a copper, drill or outline layer: left out");
    return;
  }
  throw CommandFailure(
      kExitUsage, path +
                      ": cannot tell which layer this is (no X2 TF.FileFunction, no "
                      "usual name); name it with --top, --bottom or --outline (engraver board), "
                      "or give copper as top:FILE or bottom:FILE");
}

bool has_prefix(const std::string& s, const std::string& p) {
  return s.compare(0, p.size(), p) == 0;
}

// "bottom:a,b" -> side "bottom", files {a, b}; a directory -> its PCB files.
// left_out: a directory's files that are neither Gerber nor Excellon (by name or content).
std::vector<std::string> expand_input(const std::string& input, std::string* side, bool* directory,
                                      std::string* stripped = nullptr,
                                      std::vector<std::string>* left_out = nullptr) {
  std::string rest = input;
  for (const char* s : {"top:", "bottom:"}) {
    if (has_prefix(rest, s)) {
      *side = std::string(s, std::string(s).size() - 1);
      rest = rest.substr(std::string(s).size());
    }
  }
  std::vector<std::string> files;
  if (stripped) *stripped = rest;
  *directory = std::filesystem::is_directory(rest);
  if (*directory) {
    for (const auto& e : std::filesystem::directory_iterator(rest)) {
      if (!e.is_regular_file()) continue;
      const std::string p = e.path().string();
      if (pcb::pcb_file_format(p) == pcb::PcbFileFormat::kNone) {
        if (left_out) left_out->push_back(p);
        continue;
      }
      files.push_back(p);
    }
    std::sort(files.begin(), files.end());
    if (left_out) std::sort(left_out->begin(), left_out->end());
    return files;
  }
  size_t start = 0;
  while (start <= rest.size()) {
    const size_t comma = rest.find(',', start);
    const std::string f = rest.substr(start, comma == std::string::npos ? comma : comma - start);
    if (!f.empty()) files.push_back(f);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return files;
}

std::string board_name(const std::string& input_or_file) {
  std::filesystem::path p(input_or_file);
  if (p.filename().empty()) p = p.parent_path();
  return std::filesystem::is_directory(p) ? p.filename().string() : p.stem().string();
}

// The copper kind a board folder's file names show for the job's side: the side asked for,
// else top if a file is named as top copper (the default side then); kUnknown if the names
// cannot tell.
LayerKind copper_for_side(const std::string& side, const std::vector<std::string>& files) {
  if (side == "top") return LayerKind::kCopperTop;
  if (side == "bottom") return LayerKind::kCopperBottom;
  for (const std::string& f : files) {
    if (pcb::pcb_file_format(f) == pcb::PcbFileFormat::kGerber &&
        pcb::layer_kind_from_file_name(f) == LayerKind::kCopperTop)
      return LayerKind::kCopperTop;
  }
  return LayerKind::kUnknown;
}

// side_asked: --side, or "" (a "top:"/"bottom:" prefix, else the board's default side).
BoardFiles read_input(const std::string& input, const std::string& side_asked = "") {
  BoardFiles b;
  bool directory = false;
  std::string stripped;
  std::vector<std::string> left_out;
  const std::vector<std::string> files =
      expand_input(input, &b.side, &directory, &stripped, &left_out);
  for (const std::string& f : left_out)
    b.notes.push_back(f + ": neither Gerber nor Excellon (by its name or content): left out");
  if (files.empty()) throw CommandFailure(kExitUsage, input + ": no PCB files there");
  const LayerKind wanted_copper = copper_for_side(side_asked.empty() ? b.side : side_asked, files);
  for (const std::string& f : files) {
    // In a directory, only files whose names or X2 file functions say copper, drill or
    // outline are read (no silkscreen, mask or paste), and of the copper only the job
    // side's: reading the other was a fifth of a large board's planning time.
    const std::string head = directory ? pcb::read_file_head(f) : std::string();
    std::string how;  // what said which layer the file is
    if (directory && pcb::pcb_file_format(f, head) == pcb::PcbFileFormat::kExcellon)
      how = pcb::pcb_file_format(f, "") == pcb::PcbFileFormat::kExcellon ? "its name"
                                                                         : "its content (M48)";
    if (directory && pcb::pcb_file_format(f, head) == pcb::PcbFileFormat::kGerber) {
      // The file's own X2 file function first, then the table of usual names.
      LayerKind named = pcb::layer_kind_from_x2(head);
      how = "its X2 file function";
      if (named == LayerKind::kUnknown) {
        named = pcb::layer_kind_from_file_name(f);
        how = "its name";
      }
      if (named == LayerKind::kUnknown) {
        b.notes.push_back(f +
                          ": neither its name nor an X2 file function says copper, drill or "
                          "outline: left out (name it with --top, --bottom or --outline)");
        continue;
      }
      if (wanted_copper != LayerKind::kUnknown && named != wanted_copper &&
          (named == LayerKind::kCopperTop || named == LayerKind::kCopperBottom)) {
        b.notes.push_back(f + ": copper of the other side: not read for this job");
        continue;
      }
    }
    PcbLayer l = read_layer(f, LayerKind::kUnknown);
    if (l.kind == LayerKind::kUnknown && !directory && files.size() == 1 && !b.side.empty() &&
        pcb::pcb_file_format(f) == pcb::PcbFileFormat::kGerber) {
      // "top:FILE" names the copper side of a file nothing else names (Eagle's .gbx).
      l.kind = b.side == "bottom" ? LayerKind::kCopperBottom : LayerKind::kCopperTop;
      b.notes.push_back(f + ": taken as " + b.side + " copper (from the '" + b.side + ":' prefix)");
    }
    if (directory && !how.empty() && l.kind != LayerKind::kUnknown)
      b.notes.push_back(f + ": taken as " + pcb::layer_kind_name(l.kind) + " (from " + how + ")");
    add_layer(&b, std::move(l), directory);
  }
  b.from_directory = directory;
  b.name = board_name(directory ? stripped : files.front());
  if (directory && b.layers.copper_top.empty() && b.layers.copper_bottom.empty()) {
    // A board folder without copper is a folder whose copper was not recognised: planning
    // its holes alone would look like success.
    std::string msg = input +
                      ": no copper layer for the job among the folder's files (name it with "
                      "--top or --bottom; to cut only holes or an outline, give that file "
                      "itself)";
    for (const std::string& n : b.notes) msg += "\n  " + n;
    throw CommandFailure(kExitUsage, msg);
  }
  return b;
}

// ---- Planning ----

// Options each within its range (option_ranges.h) that cannot go together: usage errors
// naming them, before anything is read or planned.
void refuse_option_combinations(const BoardArgs& a) {
  if (a.clearing_tool_mm > 0 && a.narrow_passes >= a.passes)
    throw CommandFailure(kExitUsage,
                         fmt::format("--clearing-tool cuts the passes beyond --narrow-passes ({}), "
                                     "but --passes is {}: give more --passes, or no clearing tool",
                                     a.narrow_passes, a.passes));
  if (!(a.clearing_tool_mm > 0) && a.narrow_passes != 1)
    throw CommandFailure(kExitUsage,
                         "--narrow-passes counts the isolation tool's passes next to "
                         "the copper with a --clearing-tool: give the clearing tool");
  if (a.clearing_tool_mm > 0 && !(a.clearing_tool_mm > a.tool_width_mm))
    throw CommandFailure(kExitUsage, fmt::format("--clearing-tool ({} mm) must be wider than "
                                                 "--tool-width ({} mm): it cuts the outer passes",
                                                 a.clearing_tool_mm, a.tool_width_mm));
  if (a.clearing_tool_mm > 0 && a.mill_all)
    throw CommandFailure(kExitUsage,
                         "--clearing-tool cannot be combined with --mill-all (which clears all "
                         "copper-free area with the isolation tool): give one of them");
  if (!(a.tab_height_mm < a.cut_depth_mm))
    throw CommandFailure(kExitUsage, fmt::format("--tab-height ({} mm) must be below --cut-depth "
                                                 "({} mm): a tab keeps part of the board",
                                                 a.tab_height_mm, a.cut_depth_mm));
}

pcb::BoardOptions board_options(const BoardArgs& a, const MachineDefaults& d, const BoardFiles& b) {
  pcb::BoardOptions o;
  std::string side = a.side.empty() ? b.side : a.side;
  if (side.empty())
    side = b.layers.copper_top.empty() && !b.layers.copper_bottom.empty() ? "bottom" : "top";
  if (side != "top" && side != "bottom")
    throw CommandFailure(kExitUsage, "--side must be top or bottom, not '" + side + "'");
  o.side = side == "bottom" ? pcb::BoardSide::kBottom : pcb::BoardSide::kTop;
  // Copper given only for the other side would leave a job without isolation that looks
  // planned (holes and cut-out alone).
  const std::vector<PcbLayer>& job_copper =
      o.side == pcb::BoardSide::kBottom ? b.layers.copper_bottom : b.layers.copper_top;
  const std::vector<PcbLayer>& other_copper =
      o.side == pcb::BoardSide::kBottom ? b.layers.copper_top : b.layers.copper_bottom;
  if (job_copper.empty() && !other_copper.empty()) {
    const std::string other = side == "bottom" ? "top" : "bottom";
    throw CommandFailure(kExitUsage, "the job's side is " + side + " but the copper given (" +
                                         other_copper.front().path + ") is " + other +
                                         " copper: nothing to isolate; give --side " + other +
                                         " or the " + side + " copper");
  }
  refuse_option_combinations(a);
  o.isolation.tool_width_mm = a.tool_width_mm;
  o.isolation.passes = a.passes;
  o.isolation.overlap = a.overlap;
  o.isolation.clearance_mm = a.clearance_mm;
  o.isolation.mill_all = a.mill_all;
  o.isolation.clearing_tool_width_mm = a.clearing_tool_mm;
  o.isolation.narrow_passes = a.narrow_passes;
  if (!a.align_holes.empty()) {
    o.alignment.enabled = true;
    o.alignment.hole_diameter_mm = a.align_diameter_mm;
    o.alignment.hole_depth_mm = a.align_depth_mm;
    if (a.align_holes != "auto") {
      std::istringstream in(a.align_holes);
      for (std::string xy; std::getline(in, xy, ';');) {
        double x = 0, y = 0;
        char comma = 0, extra = 0;
        std::istringstream one(xy);
        if (!(one >> x >> comma >> y) || comma != ',' || (one >> extra))
          throw CommandFailure(kExitUsage, "--align-holes: '" + xy +
                                               "' is not X,Y (mm, file frame); holes are "
                                               "separated by ';', or say auto");
        o.alignment.holes_file_mm.emplace_back(x, y);
      }
    }
  } else if (!a.align_measured_mm.empty()) {
    throw CommandFailure(kExitUsage, "--align-measured needs the job's --align-holes");
  }
  o.isolation.isolate_empty_holes = a.isolate_empty_holes;
  o.isolation_depth_mm = a.depth_mm;
  o.drill_depth_mm = a.drill_depth_mm;
  o.drill_start_mm = a.drill_start_mm;
  o.drill_feed_mm_per_s = a.drill_feed_mm_s;
  o.cutout.cutter_diameter_mm = a.cutter_mm;
  o.cutout.tab_width_mm = a.tab_width_mm;
  o.cutout.tab_count = a.tabs;
  o.cutout.tab_spacing_mm = a.tab_spacing_mm;
  o.cutout_depth_mm = a.cut_depth_mm;
  o.cutout_step_mm = a.cut_step_mm;
  o.cutout_feed_mm_per_s = a.cut_feed_mm_s;
  o.tab_height_mm = a.tab_height_mm;
  o.spindle = !a.no_spindle;
  o.allow_narrow_gaps = a.allow_narrow_gaps;
  o.feed_mm_per_s = d.feed_mm_s;
  o.z_travel_mm = d.z_up_mm;
  o.margin_mm = d.margin_mm;
  o.work_width_mm = d.work_w_mm;
  o.work_height_mm = d.work_h_mm;
  return o;
}

// measured_mm: X1 Y1 X2 Y2 of the alignment holes after the flip; the job is planned once
// without, for where they should be, then turned and shifted onto them.
pcb::BoardJob plan(const BoardFiles& b, const pcb::BoardOptions& o,
                   const std::vector<double>& measured_mm = {}) {
  PcbLayer drill;  // several drill files (plated and not) make one drill layer
  pcb::BoardLayers l;
  try {
    l = b.layers.layers(&drill);
  } catch (const PlanError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
  try {
    if (measured_mm.size() == 4) {
      const pcb::BoardJob nominal = pcb::plan_board(l, o);
      if (nominal.alignment_holes_mm.size() < 2)
        throw CommandFailure(kExitUsage,
                             "--align-measured needs two alignment holes; --align-holes gave one "
                             "(a hole on the flip axis is its own mirror image): give another");
      const Point2 expected[2] = {nominal.alignment_holes_mm.at(0),
                                  nominal.alignment_holes_mm.at(1)};
      const Point2 measured[2] = {Point2(measured_mm[0], measured_mm[1]),
                                  Point2(measured_mm[2], measured_mm[3])};
      pcb::BoardOptions aligned = o;
      aligned.alignment.placement = pcb::measured_alignment(expected, measured);
      return pcb::plan_board(l, aligned);
    }
    return pcb::plan_board(l, o);
  } catch (const PlanError& e) {
    throw CommandFailure(kExitJobFailed, e.what());
  } catch (const pcb::CutoutError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
}

// ---- Measures ----

struct WireMeasure {
  size_t spline_frames = 0;
  size_t spline_bytes = 0;          // #B and #Q (or #K) frames of the isolation (as sent)
  size_t spline_bytes_compact = 0;  // the same with #K frames only (protocol 2)
  size_t spline_bytes_full = 0;     // the same with #D frames (fixed-width fields)
  size_t g1_lines = 0;              // the same curves as G1 lines at the chord tolerance
  size_t g1_bytes = 0;
  size_t g1_vertex_bytes = 0;  // G1 through every vertex of Clipper's flattened contours
};

std::string g1(const Point2& p) {
  return fmt::format("G1 X{:.3f} Y{:.3f}\n", p.x(), p.y());
}

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
    const std::vector<Point2> pts = sample(job.plan.curves[i].spline, tol_mm);
    for (size_t k = 1; k < pts.size(); ++k) {
      ++m.g1_lines;
      m.g1_bytes += g1(pts[k]).size();
    }
  }
  // Clipper's vertices (what a G-code CAM writes from the same polygons).
  m.g1_vertex_bytes = job.report.isolation_vertices * g1(Point2(123.456, 78.901)).size();
  return m;
}

// Bytes of the job's frames as sent (set-up frames left out), tool by tool in job order.
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

double peak_memory_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

nlohmann::json report_json(const pcb::BoardJob& job, const pcb::BoardOptions& o) {
  const pcb::BoardReport& r = job.report;
  nlohmann::json j;
  j["side"] = o.side == pcb::BoardSide::kBottom ? "bottom" : "top";
  j["first_tool"] = r.first_tool;
  j["islands"] = r.islands;
  j["narrow_gaps"] = nlohmann::json::array();
  for (const pcb::NarrowGap& g : r.narrow_gaps) {
    j["narrow_gaps"].push_back({{"x_mm", g.at.x / pcb::kNmPerMm},
                                {"y_mm", g.at.y / pcb::kNmPerMm},
                                {"gap_mm", g.gap_mm},
                                {"islands", {g.island_a, g.island_b}}});
  }
  j["isolation_contours"] = r.isolation_contours;
  j["isolation_length_mm"] = r.isolation_length_mm;
  j["isolation_vertices"] = r.isolation_vertices;
  j["fit"] = {{"lines", r.fit.lines}, {"arcs", r.fit.arcs}, {"cubics", r.fit.cubics}};
  j["holes"] = r.holes;
  j["holes_on_copper"] = r.holes_on_copper;
  j["slots"] = r.slots;
  j["drill_tools"] = r.drill_tools;
  j["drill_travel_file_order_mm"] = r.drill_travel_file_order_mm;
  j["drill_travel_ordered_mm"] = r.drill_travel_ordered_mm;
  j["tabs"] = r.tabs;
  j["cutout_length_mm"] = r.cutout_length_mm;
  j["tool_changes"] = r.tool_changes;
  j["notes"] = r.notes;
  j["steps"] = job.plan.steps.size();
  j["cut_length_mm"] = job.plan.cut_length_mm;
  j["rapid_length_mm"] = job.plan.rapid_length_mm;
  j["extents_mm"] = {{"min", {job.plan.extents_mm.min.x(), job.plan.extents_mm.min.y()}},
                     {"max", {job.plan.extents_mm.max.x(), job.plan.extents_mm.max.y()}}};
  return j;
}

using pcb::isolation_check_tolerance_mm;

// ---- engraver board ----

struct BoardCommand {
  std::vector<std::string> files;
  std::string top, bottom, outline;
  std::vector<std::string> drills;
  BoardArgs board;
  MachineDefaults machine;
  std::vector<double> work_mm{defaults::work_width_mm(), defaults::work_height_mm()};
  std::string outdir = "out";
  double tol_mm = defaults::kChordToleranceMm;
  bool json = false;
  bool no_check = false;
  bool no_plot = false;
};

void run_board(const BoardCommand& a) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  BoardFiles b;
  for (const std::string& f : a.files) {
    BoardFiles one = read_input(f, a.board.side);
    for (auto* kind : {&one.layers.copper_top, &one.layers.copper_bottom, &one.layers.drill,
                       &one.layers.outline})
      for (PcbLayer& l : *kind) b.layers.add(std::move(l));
    b.notes.insert(b.notes.end(), one.notes.begin(), one.notes.end());
    b.warnings.insert(b.warnings.end(), one.warnings.begin(), one.warnings.end());
    if (b.name.empty()) {
      b.name = one.name;
      b.from_directory = one.from_directory;
    }
    if (b.side.empty()) b.side = one.side;
  }
  // A layer named by its option is that kind, whatever its name or attributes say.
  if (!a.top.empty())
    b.layers.copper_top.push_back(take_warnings(&b, read_layer(a.top, LayerKind::kCopperTop)));
  if (!a.bottom.empty())
    b.layers.copper_bottom.push_back(
        take_warnings(&b, read_layer(a.bottom, LayerKind::kCopperBottom)));
  if (!a.outline.empty())
    b.layers.outline.push_back(take_warnings(&b, read_layer(a.outline, LayerKind::kOutline)));
  for (const std::string& d : a.drills)
    b.layers.drill.push_back(take_warnings(&b, read_layer(d, LayerKind::kDrill)));
  if (b.name.empty()) {
    for (const std::string& f : {a.top, a.bottom, a.outline})
      if (!f.empty() && b.name.empty()) b.name = board_name(f);
    if (b.name.empty() && !a.drills.empty()) b.name = board_name(a.drills.front());
  }
  // A bottom-side job of named files is named after its bottom copper (it took the first
  // file's name, often the top's); a folder keeps the folder's.
  const std::string side = !a.board.side.empty() ? a.board.side : b.side;
  const bool bottom = side == "bottom" || (side.empty() && b.layers.copper_top.empty() &&
                                           !b.layers.copper_bottom.empty());
  if (bottom && !b.from_directory && !b.layers.copper_bottom.empty())
    b.name = board_name(b.layers.copper_bottom.front().path);
  print_notes(b);
  MachineDefaults md = a.machine;
  md.work_w_mm = a.work_mm[0];
  md.work_h_mm = a.work_mm[1];
  const pcb::BoardOptions o = board_options(a.board, md, b);
  const pcb::BoardJob job = plan(b, o, a.board.align_measured_mm);
  for (const std::string& n : job.report.notes)
    std::cerr << "engraver: note: " << printable(n) << "\n";
  const double plan_cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const double plan_wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double plan_peak_mb = peak_memory_mb();

  nlohmann::json j = report_json(job, o);
  j["board"] = b.name;
  j["files_to_plan_cpu_s"] = plan_cpu_s;
  j["files_to_plan_wall_s"] = plan_wall_s;
  j["files_to_plan_peak_mb"] = plan_peak_mb;
  const WireMeasure w = measure_wire(job, a.tol_mm);
  j["isolation_spline_frames"] = w.spline_frames;
  j["isolation_spline_bytes"] = w.spline_bytes;
  j["isolation_spline_bytes_compact"] = w.spline_bytes_compact;
  j["isolation_spline_bytes_fixed_width"] = w.spline_bytes_full;
  j["isolation_g1_lines_same_tolerance"] = w.g1_lines;
  j["isolation_g1_bytes_same_tolerance"] = w.g1_bytes;
  j["isolation_g1_bytes_every_vertex"] = w.g1_vertex_bytes;
  j["chord_tolerance_mm"] = a.tol_mm;
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
  const std::vector<size_t> tool_bytes = bytes_per_tool(job);
  j["bytes_per_tool"] = nlohmann::json::array();
  std::string tool_bytes_text;
  for (size_t t = 0; t < job.tools.size(); ++t) {
    j["bytes_per_tool"].push_back({{"tool", t + 1},
                                   {"name", job.tools[t].label},
                                   {"diameter_mm", job.tools[t].diameter_mm},
                                   {"bytes", tool_bytes[t]}});
    tool_bytes_text += fmt::format("{}{} {} B", t ? ", " : "", job.tools[t].label, tool_bytes[t]);
  }
  bool check_ok = true;
  pcb::IsolationCheck c;
  if (!a.no_check && !job.copper_machine_nm.empty()) {
    const double tol = isolation_check_tolerance_mm(o);
    c = pcb::check_planned_isolation(job, o);
    j["check"] = {{"tolerance_mm", tol},
                  {"islands", c.islands},
                  {"copper_hits", c.hits.size()},
                  {"unseparated_pairs", c.unseparated.size()}};
    check_ok = c.hits.empty() && c.unseparated.size() <= job.report.narrow_gaps.size();
    if (!c.ok() && c.hits.empty())
      std::cerr << "engraver: isolation check: " << pcb::describe(c) << "\n";
  }
  std::filesystem::create_directories(a.outdir);
  const std::string base = (std::filesystem::path(a.outdir) / b.name).string();
  if (!a.no_plot) {
    BoardPlotInput in;
    in.title = fmt::format("{} ({} side)", b.name, j["side"].get<std::string>());
    in.job = &job;
    write_board_plot(in, base + ".board.svg", base + ".board.png");
  }
  {
    std::ofstream out(base + ".board.json");
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  }
  if (a.json) {
    std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    const pcb::BoardReport& r = job.report;
    std::cout << fmt::format(
        "{}: {} side, first tool {}\n"
        "  isolation: {} islands, {} contours, {:.1f} mm ({} lines, {} arcs, {} cubics); "
        "{} narrow gaps\n"
        "  as splines {} bytes in {} frames ({} as #K, {} as #D); as G1 at {} mm: {} "
        "bytes ({:.1f}x); G1 through every vertex: {} bytes\n"
        "  drilling: {} holes ({} on copper), {} slots, {} sizes; travel {:.1f} mm (file order "
        "{:.1f} mm)\n"
        "  cut-out: {:.1f} mm per pass, {} tabs; {} tool changes\n"
        "  bytes per tool: {}\n"
        "  files -> plan: {:.3f} s CPU, peak {:.1f} MB\n",
        b.name, j["side"].get<std::string>(), r.first_tool, r.islands, r.isolation_contours,
        r.isolation_length_mm, r.fit.lines, r.fit.arcs, r.fit.cubics, r.narrow_gaps.size(),
        w.spline_bytes, w.spline_frames, w.spline_bytes_compact, w.spline_bytes_full, a.tol_mm,
        w.g1_bytes,
        w.spline_bytes ? static_cast<double>(w.g1_bytes) / static_cast<double>(w.spline_bytes)
                       : 0.0,
        w.g1_vertex_bytes, r.holes, r.holes_on_copper, r.slots, r.drill_tools,
        r.drill_travel_ordered_mm, r.drill_travel_file_order_mm, r.cutout_length_mm, r.tabs,
        r.tool_changes, tool_bytes_text, plan_cpu_s, plan_peak_mb);
    for (const pcb::NarrowGap& g : r.narrow_gaps)
      std::cout << "  " << pcb::describe_gap(g, o.isolation) << "\n";
    for (size_t i = 0; i < job.alignment_holes_mm.size(); ++i)
      std::cout << fmt::format("  alignment hole {} at ({:.3f}, {:.3f}) mm\n", i + 1,
                               job.alignment_holes_mm[i].x(), job.alignment_holes_mm[i].y());
    if (!a.no_plot) std::cout << "  plot: " << base << ".board.svg, .png; ";
    std::cout << "report: " << base << ".board.json\n";
  }
  try {
    pcb::refuse_copper_hits(c, "the planned isolation paths");
  } catch (const pcb::CopperCutError& e) {
    throw CommandFailure(kExitCutsCopper, e.what());
  }
  if (!check_ok) throw CommandFailure(kExitJobFailed, "the isolation check failed (see above)");
}

void add_board_command(CLI::App& app) {
  auto a = std::make_shared<BoardCommand>();
  CLI::App* cmd = app.add_subcommand(
      "board",
      "Plan a whole PCB (copper, drill and outline files, each optional): isolation, drilling "
      "with tool changes, cut-out with tabs; check it, plot it, report it");
  cmd->add_option("FILES", a->files,
                  "Gerber/Excellon files or a directory of them; kinds from X2 attributes or "
                  "names");
  cmd->add_option("--top", a->top, "top copper Gerber");
  cmd->add_option("--bottom", a->bottom, "bottom copper Gerber");
  cmd->add_option("--drill", a->drills, "Excellon drill file (may be given twice: PTH, NPTH)");
  cmd->add_option("--outline", a->outline, "board outline (Edge.Cuts, profile) Gerber");
  add_board_options(cmd, &a->board);
  cmd->add_option("--feed", a->machine.feed_mm_s, "isolation feed, mm/s")->capture_default_str();
  cmd->add_option("--z-up", a->machine.z_up_mm, "travel height, mm")->capture_default_str();
  cmd->add_option("--margin", a->machine.margin_mm, "job corner from the zero, mm")
      ->capture_default_str();
  cmd->add_option("--work", a->work_mm, "work area W H in mm (default A4)")->expected(2);
  cmd->add_option("--tol", a->tol_mm, "chord tolerance for the G1 comparison, mm")
      ->check(CLI::Range(0.001, 1.0))
      ->capture_default_str();
  cmd->add_option("-o,--outdir", a->outdir, "where NAME.board.svg/.png/.json go")
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print the report as JSON");
  cmd->add_flag("--no-check", a->no_check, "skip the geometric isolation check");
  cmd->add_flag("--no-plot", a->no_plot, "write no plot");
  cmd->footer(
      "Example: engraver board board-F.Cu.gbr board-PTH.drl board-Edge.Cuts.gbr -o out\n"
      "         engraver board --side bottom samples/pcb/multivibrator/\n"
      "Then: engraver run board/ (simulate) or engraver send board/ --to tcp://HOST:PORT.\n"
      "Exit: 0 planned and checked, 1 refused (narrow gaps, work area, islands left joined), "
      "2 bad input (a file, an option out of its range or options that cannot go together), 8 "
      "the tool would cut copper.");
  cmd->callback([a] { run_board(*a); });
}

const CommandRegistrar registrar("board", add_board_command);

}  // namespace

std::string input_name(const std::string& input) {
  std::string s = input;
  const bool bottom = s.rfind("bottom:", 0) == 0;
  for (const char* side : {"top:", "bottom:"}) {
    if (s.rfind(side, 0) == 0) s = s.substr(std::string(side).size());
  }
  if (bottom && !std::filesystem::is_directory(s)) {
    // A bottom job of several files is named after its bottom copper.
    std::string side;
    bool directory = false;
    for (const std::string& f : expand_input(s, &side, &directory))
      if (pcb::layer_kind_from_file_name(f) == LayerKind::kCopperBottom) return board_name(f);
  }
  return board_name(s.substr(0, s.find(',')));
}

void add_board_options(CLI::App* cmd, BoardArgs* a) {
  const std::string g = kBoardOptionsGroup;
  cmd->add_option("--tool-width", a->tool_width_mm, "isolation: V-bit width at the depth, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--passes", a->passes, "isolation passes")->group(g)->capture_default_str();
  cmd->add_option("--overlap", a->overlap, "overlap of passes (fraction of the tool width)")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--clearance", a->clearance_mm,
                  "isolation: kept between the tool's edge and the copper for the fit and the "
                  "machine's contour error, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_flag("--mill-all", a->mill_all, "clear all copper-free area")->group(g);
  CLI::Option* clearing =
      cmd->add_option("--clearing-tool", a->clearing_tool_mm,
                      "isolation: a wider tool for the outer part of the --passes width, mm "
                      "(mounted after the isolation tool; 0: none)")
          ->group(g);
  cmd->add_option("--narrow-passes", a->narrow_passes,
                  "with --clearing-tool: passes of the isolation tool next to the copper")
      ->group(g)
      ->needs(clearing)
      ->capture_default_str();
  cmd->add_flag("--isolate-empty-holes", a->isolate_empty_holes,
                "also cut inside openings of an island that hold no other island (hatched pours)")
      ->group(g);
  cmd->add_option("--depth", a->depth_mm, "isolation depth, mm")->group(g)->capture_default_str();
  cmd->add_option("--drill-depth", a->drill_depth_mm, "drill plunge depth, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--drill-start", a->drill_start_mm, "height where each plunge starts, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--drill-feed", a->drill_feed_mm_s, "drill plunge feed, mm/s")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cutter", a->cutter_mm, "cut-out cutter diameter, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cut-depth", a->cut_depth_mm, "cut-out depth, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cut-step", a->cut_step_mm, "cut-out depth per pass, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--cut-feed", a->cut_feed_mm_s, "cut-out feed, mm/s")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--tab-width", a->tab_width_mm, "holding tab width, mm (0: none)")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--tabs", a->tabs, "holding tabs per board")->group(g)->capture_default_str();
  cmd->add_option("--tab-spacing", a->tab_spacing_mm,
                  "one tab per this much outline length, mm (instead of --tabs)")
      ->group(g);
  cmd->add_option("--tab-height", a->tab_height_mm, "board thickness the tabs keep, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--side", a->side, "top or bottom (mirrored); default: the copper given")
      ->group(g);
  cmd->add_option("--align-holes", a->align_holes,
                  "double-sided: alignment holes for pins, 'auto' (on the flip axis below and "
                  "above the board) or X,Y[;X,Y...] mm in the files' frame, each with its mirror; "
                  "drilled with the top side, which leaves the cut-out to the bottom")
      ->group(g)
      ->check(CLI::Validator(
          [](std::string& v) {
            return v.empty() ? std::string("empty: say auto, or X,Y[;X,Y...] mm") : "";
          },
          "", "not empty"));
  cmd->add_option("--align-diameter", a->align_diameter_mm, "alignment hole (pin) diameter, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--align-depth", a->align_depth_mm,
                  "alignment hole depth, through the blank into the spoil board, mm")
      ->group(g)
      ->capture_default_str();
  cmd->add_option("--align-measured", a->align_measured_mm,
                  "double-sided, second setup: X1 Y1 X2 Y2, machine mm where alignment holes 1 "
                  "and 2 were found after the flip; the job is turned and shifted onto them")
      ->group(g)
      ->expected(4);
  cmd->add_flag("--no-spindle", a->no_spindle, "no spindle on/off commands")->group(g);
  cmd->add_flag("--allow-narrow-gaps", a->allow_narrow_gaps,
                "plan even where copper is closer than the tool width (reported; exit 0 though "
                "the copper there stays joined)")
      ->group(g);
}

bool is_pcb_input(const std::string& input) {
  std::string side;
  bool directory = false;
  std::string rest = input;
  if (has_prefix(rest, "top:") || has_prefix(rest, "bottom:")) return true;
  if (std::filesystem::is_directory(rest)) return !expand_input(rest, &side, &directory).empty();
  for (const std::string& f : expand_input(rest, &side, &directory))
    if (pcb::pcb_file_format(f) != pcb::PcbFileFormat::kNone) return true;
  return false;
}

bool input_exists(const std::string& input) {
  std::string side;
  bool directory = false;
  std::string stripped;
  const std::vector<std::string> files = expand_input(input, &side, &directory, &stripped);
  if (directory) return true;
  for (const std::string& f : files)
    if (!std::filesystem::exists(f)) return false;
  return !files.empty();
}

JobPlan plan_pcb_input(const std::string& input, const BoardArgs& args, const MachineDefaults& d,
                       commands::PlannedBoard* board) {
  const BoardFiles b = read_input(input, args.side);
  print_notes(b);
  const pcb::BoardOptions o = board_options(args, d, b);
  const auto job = std::make_shared<const pcb::BoardJob>(plan(b, o, args.align_measured_mm));
  try {
    // Refused before a byte is sent (send) or the machine is simulated (run).
    const int tol_um = static_cast<int>(std::lround(d.chord_tol_mm * 1000));
    pcb::refuse_copper_hits(pcb::check_controller_isolation(*job, o, tol_um),
                            fmt::format("the controller's points at {} mm chords", d.chord_tol_mm));
  } catch (const pcb::CopperCutError& e) {
    throw CommandFailure(kExitCutsCopper, b.name + ": " + e.what());
  }
  const pcb::BoardReport& r = job->report;
  for (const std::string& n : r.notes) std::cerr << "engraver: note: " << printable(n) << "\n";
  std::cerr << fmt::format(
      "engraver: board {}: mount {} first; {} contours, {} holes, {} tool changes\n", b.name,
      r.first_tool, r.isolation_contours, r.holes, r.tool_changes);
  for (const pcb::NarrowGap& g : r.narrow_gaps)
    std::cerr << "engraver: warning: " << pcb::describe_gap(g, o.isolation) << "\n";
  if (board) {
    board->job = job;
    board->title = b.name;
    board->check_tolerance_mm = pcb::isolation_check_tolerance_mm(o);
    board->isolation_z_mm = -o.isolation_depth_mm;
  }
  return job->plan;
}

bool print_board_points_if_pcb(const std::string& input, const BoardArgs& args, double tol_mm,
                               bool csv) {
  if (!is_pcb_input(input)) return false;
  MachineDefaults d;
  // Points in the file frame: no work area applies, unless the job is turned and shifted
  // onto measured holes (machine positions): then `board`'s default work area, as it checks.
  const bool placed = !args.align_measured_mm.empty();
  if (!placed) d.work_w_mm = d.work_h_mm = 1e6;
  const BoardFiles b = read_input(input, args.side);
  print_notes(b);
  pcb::BoardOptions o = board_options(args, d, b);
  if (!placed) o.travel_width_mm = o.travel_height_mm = d.work_w_mm;
  const pcb::BoardJob job = plan(b, o, args.align_measured_mm);
  for (const std::string& n : job.report.notes)
    std::cerr << "engraver: note: " << printable(n) << "\n";
  for (const pcb::NarrowGap& g : job.report.narrow_gaps)
    std::cerr << "engraver: warning: " << pcb::describe_gap(g, o.isolation) << "\n";
  const int tol_um = static_cast<int>(std::lround(tol_mm * 1000));
  if (csv) std::cout << "tool,tool_name,tool_diameter_um,path,point,x_um,y_um,z_um\n";
  std::cout << std::fixed << std::setprecision(1);
  for (const BoardToolPath& p : board_tool_paths(job, tol_um)) {
    const pcb::BoardTool& t = job.tools[p.tool];
    if (!csv)
      std::cout << "# tool " << p.tool + 1 << " (" << t.label << "), path " << p.path << " at z "
                << p.z_um << " um: " << p.points_file_mm.size() << " points (x_um y_um)\n";
    for (size_t k = 0; k < p.points_file_mm.size(); ++k) {
      const Point2& f = p.points_file_mm[k];
      if (csv)
        std::cout << p.tool + 1 << "," << t.label << "," << t.diameter_mm * 1000 << "," << p.path
                  << "," << k << "," << f.x() * 1000 << "," << f.y() * 1000 << "," << p.z_um
                  << "\n";
      else
        std::cout << f.x() * 1000 << " " << f.y() * 1000 << "\n";
    }
  }
  return true;
}

std::vector<BoardToolPath> board_tool_paths(const pcb::BoardJob& job, int chord_tolerance_um) {
  std::vector<BoardToolPath> out;
  const JobPlan& plan = job.plan;
  size_t tool = 0;
  int32_t z_um = 0;
  bool down = false;  // the tool below the surface: a new path starts at each change of z
  bool open = false;  // the last path in `out` takes the next points
  int last_curve = -1;
  Point2 at(0, 0);
  auto start = [&]() {
    BoardToolPath p;
    p.tool = tool;
    p.path = out.size();
    p.z_um = z_um;
    out.push_back(p);
    open = true;
  };
  auto add = [&](const Point2& machine) {
    if (!open) start();
    const Point2 f = job.frame.to_file(machine);
    std::vector<Point2>& pts = out.back().points_file_mm;
    if (pts.empty() || (pts.back() - f).norm() > 1e-9) pts.push_back(f);
  };
  for (const PlanStep& s : plan.steps) {
    switch (s.kind) {
      case PlanStep::kPause:
        if (tool + 1 < job.tools.size()) ++tool;
        open = false;
        break;
      case PlanStep::kPenDown:
      case PlanStep::kPenUp:
        z_um = s.z_um;
        down = s.z_um < 0;
        open = false;
        last_curve = -1;
        break;
      case PlanStep::kRapid:
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        open = false;
        break;
      case PlanStep::kDrill: {
        const int32_t z = z_um;
        z_um = s.z_um;
        open = false;
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        add(at);
        open = false;
        z_um = z;
        break;
      }
      case PlanStep::kFeed:
        if (!down) break;
        if (!open) add(at);
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        add(at);
        break;
      case PlanStep::kSpline:
        if (!down || s.curve < 0 || s.curve == last_curve) break;
        last_curve = s.curve;
        for (const Point2& p : firmware_points_mm(plan.curves[s.curve].spline, chord_tolerance_um))
          add(p);
        at = Point2(s.to.x_um * 1e-3, s.to.y_um * 1e-3);
        break;
      default:
        break;
    }
  }
  return out;
}

}  // namespace host::cli
