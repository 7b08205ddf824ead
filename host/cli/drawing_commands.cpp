// `engraver info` (what a drawing holds) and `engraver points` (the points the firmware
// core generates for each curve).
#include <CLI/CLI.hpp>  // CLI::App

#include <cmath>              // std::llround
#include <iomanip>            // std::setprecision
#include <iostream>           // std::cout
#include <nlohmann/json.hpp>  // nlohmann::json
#include <sstream>            // std::ostringstream

#include "host/cli/board_cli.h"  // PCB input: isolation tool centres
#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/cli/pcb_info.h"
#include "host/cli/terminal_text.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/firmware_points.h"
#include "host/lib/plan/firmware_spline.h"
#include "host/lib/plan/job_defaults.h"
#include "host/lib/progress/progress_meter.h"

namespace host::cli {

namespace {

struct InfoArgs {
  std::string file;
  bool json = false;
};

struct PointsArgs {
  std::string file;
  double tol_mm = defaults::kChordToleranceMm;
  bool csv = false;
  BoardArgs board;  // PCB input: the job `board` plans
};

nlohmann::json point_json(const Point2& p) {
  return {p.x(), p.y()};
}

// One program operation as a line of text (drawing frame, mm).
std::string describe_op(const Drawing& d, const ProgramOp& op) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(3) << op.source << ": ";
  switch (op.kind) {
    case ProgramOp::kCut:
      o << "cut " << d.curves[op.curve].source << " (curve " << op.curve << ")";
      if (std::isnan(op.depth_mm)) {
        o << " at the planner's depth";
      } else {
        o << " at Z " << op.depth_mm << " mm";
      }
      break;
    case ProgramOp::kPause:
      o << "pause for the operator: \"" << op.text << "\"";
      break;
    case ProgramOp::kDwell:
      o << "dwell " << op.dwell_s << " s";
      break;
    case ProgramOp::kSpindle:
      o << "spindle " << (op.spindle_on ? "on" : "off");
      break;
    case ProgramOp::kDrill:
      o << "drill at (" << op.at.x() << ", " << op.at.y() << ") mm from Z " << op.z_start_mm
        << " to " << op.z_bottom_mm << " mm";
      if (op.feed_mm_per_s > 0) o << " at " << op.feed_mm_per_s << " mm/s";
      if (op.peck_mm > 0) o << ", pecks of " << op.peck_mm << " mm";
      if (op.dwell_s > 0) o << ", dwell " << op.dwell_s << " s at the bottom";
      o << ", then Z " << op.retract_mm << " mm";
      break;
  }
  return o.str();
}

// The whole drawing as JSON (every knot and control point).
nlohmann::json info_json(const Drawing& d) {
  nlohmann::json j;
  j["file"] = d.path;
  j["format"] = d.format;
  j["units"] = d.units;
  j["unit_to_mm"] = d.unit_to_mm;
  j["entities"] = d.entity_counts;
  const Extents e = d.extents();
  if (!e.empty()) {
    j["extents_mm"] = {{"min", point_json(e.min)},
                       {"max", point_json(e.max)},
                       {"width", e.width()},
                       {"height", e.height()}};
  } else {
    j["extents_mm"] = nullptr;
  }
  j["curves"] = nlohmann::json::array();
  for (const Curve& c : d.curves) {
    nlohmann::json cj;
    cj["source"] = c.source;
    cj["kind"] = c.kind;
    cj["degree"] = c.spline.degree;
    cj["rational"] = c.spline.rational();
    cj["knots"] = c.spline.knots;
    cj["control_points_mm"] = nlohmann::json::array();
    for (const Point2& p : c.spline.control) cj["control_points_mm"].push_back(point_json(p));
    if (c.spline.rational()) cj["weights"] = c.spline.weights;
    cj["start_mm"] = point_json(start_point(c.spline));
    cj["end_mm"] = point_json(end_point(c.spline));
    j["curves"].push_back(cj);
  }
  j["program"] = nlohmann::json::array();
  for (const ProgramOp& op : d.program) j["program"].push_back(describe_op(d, op));
  j["problems"] = d.warnings;
  return j;
}

// Numbers in a list, space separated, at most `limit` shown.
template <typename T>
std::string list(const std::vector<T>& v, size_t limit) {
  std::ostringstream o;
  o << std::setprecision(10);
  for (size_t i = 0; i < v.size() && i < limit; ++i) o << (i ? " " : "") << v[i];
  if (v.size() > limit) o << " ... (" << v.size() << " in all)";
  return o.str();
}

void print_info(const Drawing& d, std::ostream& out) {
  out << std::fixed << std::setprecision(3);
  out << "file:     " << d.path << "\n";
  out << "format:   " << d.format << "\n";
  out << "units:    " << d.units << " (1 unit = " << d.unit_to_mm << " mm)\n";
  out << "entities: ";
  if (d.entity_counts.empty()) out << "none";
  bool first = true;
  for (const auto& e : d.entity_counts) {
    out << (first ? "" : ", ") << e.first << " " << e.second;
    first = false;
  }
  out << "\n";
  const Extents e = d.extents();
  if (e.empty()) {
    out << "extents:  (no curves)\n";
  } else {
    out << "extents:  x " << e.min.x() << " .. " << e.max.x() << " mm, y " << e.min.y() << " .. "
        << e.max.y() << " mm (" << e.width() << " x " << e.height() << " mm)\n";
  }
  out << "curves:   " << d.curves.size() << "\n";
  for (size_t i = 0; i < d.curves.size(); ++i) {
    const Curve& c = d.curves[i];
    const BSpline& s = c.spline;
    const Point2 a = start_point(s), b = end_point(s);
    out << "  " << i << ": " << c.source << ": degree " << s.degree
        << (s.rational() ? ", rational" : "") << ", " << s.control.size() << " control points, "
        << s.knots.size() << " knots, from (" << a.x() << ", " << a.y() << ") to (" << b.x() << ", "
        << b.y() << ") mm\n";
    if (c.kind == "SPLINE") {
      out << "       knots: " << list(s.knots, 24) << "\n";
      std::ostringstream cp;
      cp << std::fixed << std::setprecision(4);
      for (size_t k = 0; k < s.control.size() && k < 16; ++k) {
        cp << (k ? " " : "") << "(" << s.control[k].x() << ", " << s.control[k].y() << ")";
      }
      if (s.control.size() > 16) cp << " ...";
      out << "       control points (mm): " << cp.str() << "\n";
      if (s.rational()) out << "       weights: " << list(s.weights, 24) << "\n";
    }
  }
  if (!d.program.empty()) {
    out << "program:  " << d.program.size()
        << " operations, planned in this order (nothing reordered):\n";
    const size_t limit = 200;
    for (size_t i = 0; i < d.program.size() && i < limit; ++i)
      out << "  " << describe_op(d, d.program[i]) << "\n";
    if (d.program.size() > limit) out << "  ... (" << d.program.size() - limit << " more)\n";
  }
  out << "problems: " << (d.warnings.empty() ? "none" : "") << "\n";
  for (const std::string& w : d.warnings) out << "  - " << w << "\n";
}

void run_info(const InfoArgs& a) {
  if (print_pcb_info_if_pcb(a.file, a.json)) return;  // Gerber, Excellon
  const Drawing d = import_drawing(a.file);
  if (a.json) {
    std::cout << info_json(d).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    std::ostringstream out;  // names and messages quote the file: shown terminal-safe
    print_info(d, out);
    std::cout << printable(out.str());
  }
}

// The board options on a drawing are refused rather than ignored.
void refuse_board_options_for_drawings(const CLI::App& cmd, const std::string& file) {
  if (is_pcb_input(file)) return;
  for (const CLI::Option* o : cmd.get_options()) {
    if (o->count() > 0 && o->get_group() == kBoardOptionsGroup)
      throw CLI::ValidationError(o->get_name() +
                                 " is for PCB files (Gerber, Excellon, a board folder), not "
                                 "drawings");
  }
}

void run_points(const PointsArgs& a) {
  const double tol_um = a.tol_mm * 1000.0;
  if (!(tol_um >= 1.0 - 1e-9 && tol_um <= 10000.0 + 1e-9)) {
    throw CommandFailure(kExitUsage,
                         "--tol must be between 0.001 and 10 mm (the firmware "
                         "steps with a whole-micrometre chord tolerance)");
  }
  const int tol = static_cast<int>(std::llround(tol_um));
  if (print_board_points_if_pcb(a.file, a.board, a.tol_mm, a.csv)) return;  // tool centres
  const Drawing d = import_drawing(a.file);
  for (const std::string& w : d.warnings) std::cerr << "warning: " << printable(w) << "\n";
  std::cout << std::fixed << std::setprecision(3);
  if (a.csv) std::cout << "curve,x_mm,y_mm\n";
  ProgressMeter progress("points", "curves", std::cerr, ProgressMeter::for_stderr());
  for (size_t i = 0; i < d.curves.size(); ++i) {
    progress.update(i, d.curves.size());
    std::vector<Point2> pts;
    try {
      pts = firmware_points_mm(d.curves[i].spline, tol);
    } catch (const ConversionError& e) {
      throw CommandFailure(kExitJobFailed, d.path + ": curve " + std::to_string(i) + " (" +
                                               d.curves[i].source + "): " + e.what());
    }
    if (!a.csv) {
      std::cout << "# curve " << i << ": " << printable(d.curves[i].source) << ": " << pts.size()
                << " points (x_mm y_mm)\n";
    }
    for (const Point2& p : pts) {
      if (a.csv) {
        std::cout << i << "," << p.x() << "," << p.y() << "\n";
      } else {
        std::cout << p.x() << " " << p.y() << "\n";
      }
    }
  }
  progress.update(d.curves.size(), d.curves.size());
}

void add_drawing_commands(CLI::App& app) {
  auto info_args = std::make_shared<InfoArgs>();
  CLI::App* info = app.add_subcommand(
      "info",
      "Show what a drawing holds: entities by type, curves (degree, rational, knots, "
      "control points), extents, units and the problems found; of a Gerber or Excellon file, "
      "its layer, apertures or tools, polygons and holes");
  info->add_option("FILE", info_args->file,
                   "drawing (DXF, G-code) or PCB file (Gerber, Excellon, a board folder)")
      ->required();
  info->add_flag("--json", info_args->json, "print JSON instead of text");
  info->footer(
      "Examples:\n"
      "  engraver info samples/engraver-word.dxf\n"
      "  engraver info --json board_back.ngc > board_back.json\n"
      "  engraver info board-F.Cu.gbr\n"
      "Exit codes: 0 shown; 2 bad option, or the file cannot be read or imported (the message "
      "names the file and the place in it).");
  info->callback([info_args]() { run_info(*info_args); });

  auto points_args = std::make_shared<PointsArgs>();
  CLI::App* points =
      app.add_subcommand("points",
                         "Print the points the firmware's point generator produces for each curve "
                         "(drawing frame, mm); for PCB files, every tool-centre path of the board "
                         "job, tool by tool (files' frame, um)");
  points
      ->add_option("FILE", points_args->file,
                   "drawing (DXF, G-code) or PCB files (Gerber, Excellon, a board folder)")
      ->required();
  points->add_option("--tol", points_args->tol_mm, "chord tolerance in mm (0.001 .. 10)")
      ->capture_default_str();
  points->add_flag("--csv", points_args->csv,
                   "CSV: header, then curve,x_mm,y_mm rows (PCB files: tool,tool_name,"
                   "tool_diameter_um,path,point,x_um,y_um,z_um)");
  add_board_options(points, &points_args->board);
  points->footer(
      "Examples:\n"
      "  engraver points samples/engraver-word.dxf --tol 0.005 --csv > points.csv\n"
      "  engraver points board_outline.ngc --tol 0.01\n"
      "  engraver points board/ --side bottom --tool-width 0.1 --passes 3 --csv > paths.csv\n"
      "Exit codes: 0 printed; 1 a curve the firmware cannot hold; 2 bad option, or the file "
      "cannot be read or imported.");
  points->callback([points, points_args]() {
    refuse_board_options_for_drawings(*points, points_args->file);
    run_points(*points_args);
  });
}

const CommandRegistrar registrar("drawing", add_drawing_commands);

}  // namespace

}  // namespace host::cli
