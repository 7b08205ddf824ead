#include "host/cli/pcb_info.h"

#include <algorithm>          // std::min, std::max
#include <iomanip>            // std::setprecision
#include <iostream>           // std::cout
#include <map>                // std::map
#include <nlohmann/json.hpp>  // nlohmann::json

#include "host/cli/exit_codes.h"
#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_reader.h"
#include "host/lib/pcb/pcb_file_names.h"

namespace host::cli {

namespace {

using host::pcb::PcbLayer;

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

void print_text(const PcbLayer& l, const char* format) {
  const Box b = extents(l);
  const Counts c = count(l);
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "file:      " << l.path << "\n";
  std::cout << "format:    " << format << "\n";
  std::cout << "layer:     " << host::pcb::layer_kind_name(l.kind) << "\n";
  std::cout << "units:     " << (l.units.empty() ? "not given" : l.units) << "\n";
  if (b.empty) {
    std::cout << "extents:   (nothing drawn)\n";
  } else {
    std::cout << "extents:   x " << b.x0 << " .. " << b.x1 << " mm, y " << b.y0 << " .. " << b.y1
              << " mm (" << b.x1 - b.x0 << " x " << b.y1 - b.y0 << " mm)\n";
  }
  if (l.kind == host::pcb::LayerKind::kDrill) {
    std::cout << "tools:     " << l.apertures_or_tools << " defined, " << c.tools.size()
              << " used\n";
    for (const auto& t : c.tools) {
      std::cout << "  T" << t.first << ": " << t.second.first << " mm, " << t.second.second
                << " holes and slots\n";
    }
    std::cout << "holes:     " << l.holes.size() << "\n";
    std::cout << "slots:     " << l.slots.size() << "\n";
  } else {
    std::cout << "apertures: " << l.apertures_or_tools << "\n";
    if (l.outline_paths_are_open) {
      size_t closed = 0;
      for (const auto& p : l.polygons_nm) closed += p.size() > 2 && p.front() == p.back();
      std::cout << "paths:     " << l.polygons_nm.size() << " centre lines (" << closed
                << " closed), " << c.vertices << " vertices\n";
    } else {
      std::cout << "polygons:  " << c.outers << " copper areas, " << c.holes << " holes in them, "
                << c.vertices << " vertices (arcs within " << l.arc_tolerance_nm * 1e-3 << " um)\n";
    }
  }
  std::cout << "notes:     " << (l.notes.empty() ? "none" : "") << "\n";
  for (const std::string& n : l.notes) std::cout << "  - " << n << "\n";
}

void print_json(const PcbLayer& l, const char* format) {
  const Box b = extents(l);
  const Counts c = count(l);
  nlohmann::json j;
  j["file"] = l.path;
  j["format"] = format;
  j["layer"] = host::pcb::layer_kind_name(l.kind);
  j["units"] = l.units;
  j["extents_mm"] = b.empty ? nlohmann::json(nullptr)
                            : nlohmann::json{{"min", {b.x0, b.y0}}, {"max", {b.x1, b.y1}}};
  j["apertures_or_tools"] = l.apertures_or_tools;
  j["polygons"] = c.outers;
  j["polygon_holes"] = c.holes;
  j["vertices"] = c.vertices;
  j["open_paths"] = l.outline_paths_are_open;
  j["holes"] = l.holes.size();
  j["slots"] = l.slots.size();
  j["arc_tolerance_nm"] = l.arc_tolerance_nm;
  nlohmann::json tools = nlohmann::json::object();
  for (const auto& t : c.tools) {
    tools["T" + std::to_string(t.first)] = {{"diameter_mm", t.second.first},
                                            {"count", t.second.second}};
  }
  j["tools"] = tools;
  j["notes"] = l.notes;
  std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

}  // namespace

bool print_pcb_info_if_pcb(const std::string& path, bool json) {
  const host::pcb::PcbFileFormat f = host::pcb::pcb_file_format(path);
  if (f == host::pcb::PcbFileFormat::kNone) return false;
  const bool gerber = f == host::pcb::PcbFileFormat::kGerber;
  PcbLayer layer;
  try {
    layer = gerber ? host::pcb::read_gerber_file(path) : host::pcb::read_excellon_file(path);
  } catch (const host::pcb::PcbReadError& e) {
    throw CommandFailure(kExitUsage, e.what());
  }
  const char* format = gerber ? "Gerber RS-274X" : "Excellon";
  if (json) {
    print_json(layer, format);
  } else {
    print_text(layer, format);
  }
  return true;
}

}  // namespace host::cli
