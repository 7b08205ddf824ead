// Reading a board's files from memory (see board_files.h).
#include "host/lib/pcb/board_files.h"

#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_include.h"
#include "host/lib/pcb/gerber_reader.h"

namespace host::pcb {

const char* const kGerberNotADrillFile = "holds Gerber, not Excellon: no drill file";

PcbFileFormat board_file_format(const std::string& name, const std::string& text) {
  return pcb_file_format(name, text.substr(0, 4096));
}

PcbLayer read_board_text(const std::string& text, const std::string& name, LayerKind kind) {
  // An upload's bytes (a file's text comes without the mark: read_pcb_file_text).
  if (const size_t bom = utf8_bom_length(text))
    return read_board_text(text.substr(bom), name, kind);
  const PcbFileFormat f = board_file_format(name, text);
  if (f == PcbFileFormat::kExcellon || (f == PcbFileFormat::kNone && kind == LayerKind::kDrill)) {
    PcbLayer l = read_excellon_text(text, name);
    l.kind = LayerKind::kDrill;
    return l;
  }
  if (f == PcbFileFormat::kGerber && kind == LayerKind::kDrill)
    throw PcbReadError(name + ": " + kGerberNotADrillFile);
  if (f == PcbFileFormat::kGerber || kind != LayerKind::kUnknown) {
    GerberOptions o;
    o.forced_kind = kind;
    PcbLayer l = read_gerber_text(text, name, o);
    if (kind != LayerKind::kUnknown) {
      l.kind = kind;
    } else if (l.kind == LayerKind::kDrill) {
      // A drill drawing or map (OrCAD's Gerber .drd): a picture of the holes, not holes.
      l.kind = LayerKind::kUnknown;
      l.notes.push_back(std::string("warning: ") + kGerberNotADrillFile);
    }
    return l;
  }
  throw PcbReadError(name + ": not a Gerber or Excellon file");
}

PcbLayer read_board_file(const std::string& path, LayerKind kind) {
  const std::string text = read_pcb_file_text(path);
  if (board_file_format(path, text) != PcbFileFormat::kGerber)
    return read_board_text(text, path, kind);
  return read_board_text(expand_gerber_includes(text, path), path, kind);
}

bool BoardFileSet::add(PcbLayer layer) {
  switch (layer.kind) {
    case LayerKind::kCopperTop:
      copper_top.push_back(std::move(layer));
      return true;
    case LayerKind::kCopperBottom:
      copper_bottom.push_back(std::move(layer));
      return true;
    case LayerKind::kDrill:
      drill.push_back(std::move(layer));
      return true;
    case LayerKind::kOutline:
      outline.push_back(std::move(layer));
      return true;
    case LayerKind::kUnknown:
      break;
  }
  return false;
}

BoardLayers BoardFileSet::layers(PcbLayer* drill_storage) const {
  auto once = [](const std::vector<PcbLayer>& v, const char* what) -> const PcbLayer* {
    if (v.size() > 1) {
      throw PlanError(std::string("two files for the ") + what + ": " + v[0].path + " and " +
                      v[1].path);
    }
    return v.empty() ? nullptr : &v.front();
  };
  BoardLayers l;
  l.copper_top = once(copper_top, "top copper");
  l.copper_bottom = once(copper_bottom, "bottom copper");
  l.outline = once(outline, "outline");
  if (!drill.empty()) {
    *drill_storage = drill.front();
    for (size_t i = 1; i < drill.size(); ++i) {
      drill_storage->holes.insert(drill_storage->holes.end(), drill[i].holes.begin(),
                                  drill[i].holes.end());
      drill_storage->slots.insert(drill_storage->slots.end(), drill[i].slots.begin(),
                                  drill[i].slots.end());
      drill_storage->path += " + " + drill[i].path;
    }
    l.drill = drill_storage;
  }
  return l;
}

std::string board_name_from_files(const std::vector<std::string>& names) {
  if (names.empty()) return "board";
  std::string common = names.front();
  for (const std::string& n : names) {
    size_t k = 0;
    while (k < common.size() && k < n.size() && common[k] == n[k]) ++k;
    common.resize(k);
  }
  if (names.size() == 1) {
    const size_t dot = common.rfind('.');
    if (dot != std::string::npos && dot > 0) common.resize(dot);
  }
  while (!common.empty() && (common.back() == '-' || common.back() == '_' || common.back() == '.' ||
                             common.back() == ' '))
    common.pop_back();
  if (!common.empty()) return common;
  const std::string& first = names.front();
  const size_t dot = first.rfind('.');
  return dot == std::string::npos || dot == 0 ? first : first.substr(0, dot);
}

}  // namespace host::pcb
