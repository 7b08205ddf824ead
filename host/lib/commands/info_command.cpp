// `engraver info` and `engraver points` as functions (see info_command.h).
#include "host/lib/commands/info_command.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>   // std::min, std::max
#include <cmath>       // std::isnan, std::llround
#include <filesystem>  // std::filesystem::is_directory
#include <iomanip>     // std::setprecision
#include <map>         // std::map
#include <sstream>     // std::ostringstream

#include "host/lib/commands/board_input.h"  // read_board_folder
#include "host/lib/commands/exit_codes.h"   // CommandFailure
#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_reader.h"
#include "host/lib/pcb/pcb_file_names.h"
#include "host/lib/plan/counted.h"  // counted: "1 hole", "2 holes"
#include "host/lib/plan/firmware_points.h"
#include "host/lib/plan/firmware_spline.h"
#include "host/lib/plan/job_defaults.h"  // kChordToleranceRangeMm

namespace host::commands {

namespace {

using pcb::PcbLayer;

struct Box {
  bool empty = true;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // mm
  void add(double x_nm, double y_nm, double r_nm = 0) {
    const double xa = (x_nm - r_nm) * 1e-6, xb = (x_nm + r_nm) * 1e-6;
    const double ya = (y_nm - r_nm) * 1e-6, yb = (y_nm + r_nm) * 1e-6;
    if (empty) {
      x0 = xa, x1 = xb, y0 = ya, y1 = yb;
      empty = false;
      return;
    }
    x0 = std::min(x0, xa), x1 = std::max(x1, xb), y0 = std::min(y0, ya), y1 = std::max(y1, yb);
  }
};

// "x A .. B mm, y C .. D mm (W x H mm)" to the micrometre, the size the difference of the
// ends as printed: from the box itself it could differ from them in the last digit (a round
// flash's polygon reaches 0.2497 mm on either side: "-0.250 .. 0.250 (0.499)").
std::string extents_text(double x0, double y0, double x1, double y1) {
  const long long ax = std::llround(x0 * 1000), bx = std::llround(x1 * 1000);
  const long long ay = std::llround(y0 * 1000), by = std::llround(y1 * 1000);
  const auto mm = [](long long um) {
    return fmt::format("{:.3f}", static_cast<double>(um) / 1000);
  };
  return fmt::format("x {} .. {} mm, y {} .. {} mm ({} x {} mm)", mm(ax), mm(bx), mm(ay), mm(by),
                     mm(bx - ax), mm(by - ay));
}

// A length in mm at the text's resolution (um), for JSON: 0.8, not 0.7999999999999999.
double um_resolution_mm(double mm) {
  return static_cast<double>(std::llround(mm * 1000)) / 1000;
}

// Corners, width and height for JSON at the text's resolution (um), the size from the
// rounded ends as there.
nlohmann::json extents_json(double x0, double y0, double x1, double y1) {
  const double ax = um_resolution_mm(x0), ay = um_resolution_mm(y0);
  const double bx = um_resolution_mm(x1), by = um_resolution_mm(y1);
  return {{"min", {ax, ay}},
          {"max", {bx, by}},
          {"width", um_resolution_mm(bx - ax)},
          {"height", um_resolution_mm(by - ay)}};
}

Box extents(const PcbLayer& l) {
  Box b;
  for (const auto& path : l.polygons_nm) {
    for (const auto& p : path) b.add(static_cast<double>(p.X), static_cast<double>(p.Y));
  }
  for (const auto& h : l.holes) {
    b.add(static_cast<double>(h.at.x), static_cast<double>(h.at.y),
          static_cast<double>(h.diameter_nm) / 2);
  }
  for (const auto& s : l.slots) {
    const double r = static_cast<double>(s.diameter_nm) / 2;
    b.add(static_cast<double>(s.from.x), static_cast<double>(s.from.y), r);
    b.add(static_cast<double>(s.to.x), static_cast<double>(s.to.y), r);
  }
  return b;
}

// An outline's centre lines that do not close (0 for a layer of polygons).
size_t open_paths(const PcbLayer& l) {
  if (!l.outline_paths_are_open) return 0;
  size_t open = 0;
  for (const auto& p : l.polygons_nm) open += !(p.size() > 2 && p.front() == p.back());
  return open;
}

struct Counts {
  size_t outers = 0, holes = 0, vertices = 0;
  std::map<int, std::pair<double, size_t>> tools;  // tool -> (diameter mm, holes + slots)
};

Counts count(const PcbLayer& l) {
  Counts c;
  for (const auto& path : l.polygons_nm) {
    c.vertices += path.size();
    if (l.outline_paths_are_open || ClipperLib::Orientation(path)) {
      ++c.outers;
    } else {
      ++c.holes;
    }
  }
  for (const auto& h : l.holes) {
    auto& t = c.tools[h.tool];
    t.first = static_cast<double>(h.diameter_nm) * 1e-6;
    ++t.second;
  }
  for (const auto& s : l.slots) {
    auto& t = c.tools[s.tool];
    t.first = static_cast<double>(s.diameter_nm) * 1e-6;
    ++t.second;
  }
  return c;
}

}  // namespace

std::string pcb_info_text(const PcbFileInfo& info) {
  const PcbLayer& l = info.layer;
  const std::string& format = info.format;
  std::ostringstream out;
  const Box b = extents(l);
  const Counts c = count(l);
  out << std::fixed << std::setprecision(3);
  out << "file:      " << l.path << "\n";
  out << "format:    " << format << "\n";
  out << "layer:     " << pcb::layer_kind_name(l.kind) << "\n";
  out << "units:     " << (l.units.empty() ? "not given" : l.units) << "\n";
  if (b.empty) {
    out << "extents:   (nothing drawn)\n";
  } else {
    out << "extents:   " << extents_text(b.x0, b.y0, b.x1, b.y1) << "\n";
  }
  if (l.kind == pcb::LayerKind::kDrill) {
    out << "tools:     " << l.apertures_or_tools << " defined, " << c.tools.size() << " used\n";
    for (const auto& t : c.tools) {
      out << "  T" << t.first << ": " << t.second.first << " mm, "
          << counted(t.second.second, "hole or slot", "holes and slots") << "\n";
    }
    out << "holes:     " << l.holes.size() << "\n";
    out << "slots:     " << l.slots.size() << "\n";
  } else {
    out << "apertures: " << l.apertures_or_tools << "\n";
    if (l.outline_paths_are_open) {
      const size_t closed = l.polygons_nm.size() - open_paths(l);
      out << "paths:     " << counted(l.polygons_nm.size(), "centre line") << " (" << closed
          << " closed), " << counted(c.vertices, "vertex", "vertices") << "\n";
    } else {
      out << "polygons:  " << counted(c.outers, "copper area") << ", " << counted(c.holes, "hole")
          << " in them, " << counted(c.vertices, "vertex", "vertices") << " (arcs within "
          << l.arc_tolerance_nm * 1e-3 << " um)\n";
    }
  }
  out << "notes:     " << (l.notes.empty() ? "none" : "") << "\n";
  for (const std::string& n : l.notes) out << "  - " << n << "\n";
  return out.str();
}

nlohmann::json pcb_info_json(const PcbFileInfo& info) {
  const PcbLayer& l = info.layer;
  const Box b = extents(l);
  const Counts c = count(l);
  nlohmann::json j;
  j["file"] = l.path;
  j["format"] = info.format;
  j["layer"] = pcb::layer_kind_name(l.kind);
  j["units"] = l.units;
  // As a drawing's: corners, width and height, all in mm (the key says the unit).
  j["extents_mm"] = b.empty ? nlohmann::json(nullptr) : extents_json(b.x0, b.y0, b.x1, b.y1);
  j["apertures_or_tools"] = l.apertures_or_tools;
  j["polygons"] = c.outers;
  j["polygon_holes"] = c.holes;
  j["vertices"] = c.vertices;
  j["open_paths"] = open_paths(l);
  j["holes"] = l.holes.size();
  j["slots"] = l.slots.size();
  j["arc_tolerance_nm"] = l.arc_tolerance_nm;
  nlohmann::json tools = nlohmann::json::object();
  for (const auto& t : c.tools) {
    tools["T" + std::to_string(t.first)] = {{"diameter_mm", um_resolution_mm(t.second.first)},
                                            {"count", t.second.second}};
  }
  j["tools"] = tools;
  j["notes"] = l.notes;
  return j;
}

namespace {

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

}  // namespace

nlohmann::json drawing_info_json(const Drawing& d) {
  nlohmann::json j;
  j["file"] = d.path;
  j["format"] = d.format;
  j["units"] = d.units;
  j["unit_to_mm"] = d.unit_to_mm;
  j["entities"] = d.entity_counts;
  const Extents e = d.extents();
  j["extents_mm"] = e.empty() ? nlohmann::json(nullptr)
                              : extents_json(e.min.x(), e.min.y(), e.max.x(), e.max.y());
  j["curves"] = nlohmann::json::array();
  for (const Curve& c : d.curves) {
    nlohmann::json cj;
    cj["source"] = c.source;
    cj["kind"] = c.kind;
    const BSpline s = c.spline();
    cj["degree"] = s.degree;
    cj["rational"] = s.rational();
    cj["knots"] = s.knots;
    cj["control_points_mm"] = nlohmann::json::array();
    for (const Point2& p : s.control) cj["control_points_mm"].push_back(point_json(p));
    if (s.rational()) cj["weights"] = s.weights;
    cj["start_mm"] = point_json(start_point(s));
    cj["end_mm"] = point_json(end_point(s));
    j["curves"].push_back(cj);
  }
  j["program"] = nlohmann::json::array();
  for (const ProgramOp& op : d.program) j["program"].push_back(describe_op(d, op));
  j["problems"] = d.warnings;
  return j;
}

namespace {

// Numbers in a list, space separated, at most `limit` shown.
template <typename T>
std::string list(const std::vector<T>& v, size_t limit) {
  std::ostringstream o;
  o << std::setprecision(10);
  for (size_t i = 0; i < v.size() && i < limit; ++i) o << (i ? " " : "") << v[i];
  if (v.size() > limit) o << " ... (" << v.size() << " in all)";
  return o.str();
}

}  // namespace

std::string drawing_info_text(const Drawing& d) {
  std::ostringstream out;
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
    out << "extents:  " << extents_text(e.min.x(), e.min.y(), e.max.x(), e.max.y()) << "\n";
  }
  out << "curves:   " << d.curves.size() << "\n";
  for (size_t i = 0; i < d.curves.size(); ++i) {
    const Curve& c = d.curves[i];
    const BSpline s = c.spline();
    const Point2 a = start_point(s), b = end_point(s);
    out << "  " << i << ": " << c.source << ": degree " << s.degree
        << (s.rational() ? ", rational" : "") << ", " << s.control.size() << " control points, "
        << s.knots.size() << " knots, from (" << a.x() << ", " << a.y() << ") to (" << b.x() << ", "
        << b.y() << ") mm\n";
    if (std::string(c.kind) == "SPLINE") {
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
    out << "program:  " << counted(d.program.size(), "operation")
        << ", planned in this order (nothing reordered):\n";
    const size_t limit = 200;
    for (size_t i = 0; i < d.program.size() && i < limit; ++i)
      out << "  " << describe_op(d, d.program[i]) << "\n";
    if (d.program.size() > limit) out << "  ... (" << d.program.size() - limit << " more)\n";
  }
  out << "problems: " << (d.warnings.empty() ? "none" : "") << "\n";
  for (const std::string& w : d.warnings) out << "  - " << w << "\n";
  return out.str();
}

std::optional<PcbFileInfo> read_pcb_file_info(const std::string& path) {
  const pcb::PcbFileFormat f = pcb::pcb_file_format(path);
  if (f == pcb::PcbFileFormat::kNone) return std::nullopt;
  const bool gerber = f == pcb::PcbFileFormat::kGerber;
  PcbFileInfo info;
  try {
    info.layer = gerber ? pcb::read_gerber_file(path) : pcb::read_excellon_file(path);
  } catch (const pcb::PcbReadError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
  info.format = gerber ? "Gerber RS-274X" : "Excellon";
  return info;
}

std::optional<BoardFolderInfo> read_board_folder_info(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) return std::nullopt;
  const BoardFiles b = read_board_folder(path);
  BoardFolderInfo info;
  info.folder = path;
  info.board = b.name;
  info.files = b.notes;
  const pcb::BoardFileSet& l = b.layers;
  for (const auto* kind : {&l.copper_top, &l.copper_bottom, &l.drill, &l.outline}) {
    for (const PcbLayer& layer : *kind) {
      // Gerber content is never read as a drill layer (board_files.h).
      const bool drill = layer.kind == pcb::LayerKind::kDrill;
      info.layers.push_back(PcbFileInfo{layer, drill ? "Excellon" : "Gerber RS-274X"});
    }
  }
  return info;
}

std::string board_folder_info_text(const BoardFolderInfo& info) {
  std::ostringstream out;
  out << "folder:    " << info.folder << " (board '" << info.board << "', "
      << counted(info.layers.size(), "layer") << " read)\n";
  out << "files:\n";
  for (const std::string& f : info.files) out << "  - " << f << "\n";
  for (const PcbFileInfo& layer : info.layers) out << "\n" << pcb_info_text(layer);
  return out.str();
}

nlohmann::json board_folder_info_json(const BoardFolderInfo& info) {
  nlohmann::json j;
  j["folder"] = info.folder;
  j["board"] = info.board;
  j["files"] = info.files;
  j["layers"] = nlohmann::json::array();
  for (const PcbFileInfo& layer : info.layers) j["layers"].push_back(pcb_info_json(layer));
  return j;
}

int points_tolerance_um(double tol_mm) {
  const double tol_um = tol_mm * 1000.0;
  const defaults::Range r = defaults::kChordToleranceRangeMm;
  if (!(tol_um >= r.min * 1000.0 - 1e-9 && tol_um <= r.max * 1000.0 + 1e-9)) {
    throw CommandFailure(kExitUsage,
                         fmt::format("--tol must be between {:g} and {:g} mm (the firmware "
                                     "steps with a whole-micrometre chord tolerance)",
                                     r.min, r.max));
  }
  return static_cast<int>(std::llround(tol_um));
}

std::vector<Point2> curve_points(const Drawing& d, size_t curve, int tol_um) {
  try {
    return firmware_points_mm(d.curves[curve].spline(), tol_um);
  } catch (const ConversionError& e) {
    throw CommandFailure(kExitJobFailed, d.path + ": curve " + std::to_string(curve) + " (" +
                                             d.curves[curve].source + "): " + e.what());
  }
}

}  // namespace host::commands
