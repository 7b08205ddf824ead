#include "host/lib/pcb/pcb_file_names.h"

#include <cctype>   // std::isalnum
#include <utility>  // std::pair
#include <vector>   // std::vector

#include "host/lib/drawing/drawing.h"    // starts_like_excellon
#include "host/lib/drawing/file_text.h"  // lower_ascii

namespace host::pcb {

namespace {

// The file name without folders, lower case.
std::string base_name(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return lower_ascii(slash == std::string::npos ? path : path.substr(slash + 1));
}

std::string extension(const std::string& name) {
  const size_t dot = name.rfind('.');
  return dot == std::string::npos ? std::string() : name.substr(dot);
}

bool contains(const std::string& s, const char* part) {
  return s.find(part) != std::string::npos;
}

bool ends_with(const std::string& s, const char* tail) {
  const std::string t(tail);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// What a word of a file name (a run of letters and digits) says of a layer no job cuts:
// KiCad's F.SilkS, F.Mask, F.Paste, F.Fab, F.CrtYd, Dwgs.User; EAGLE's tPlace, tStop,
// tCream; the usual English words. Whole words only: a project named "fabric" or "MaskRom"
// is not a fabrication or mask layer.
const char* other_layer_word(const std::string& word) {
  static const std::pair<const char*, const char*> kWords[] = {
      {"silk", "silkscreen"},        {"silks", "silkscreen"},      {"silkscreen", "silkscreen"},
      {"legend", "silkscreen"},      {"overlay", "silkscreen"},    {"tplace", "silkscreen"},
      {"bplace", "silkscreen"},      {"paste", "paste"},           {"pastemask", "paste"},
      {"stencil", "paste"},          {"cream", "paste"},           {"tcream", "paste"},
      {"bcream", "paste"},           {"mask", "solder mask"},      {"soldermask", "solder mask"},
      {"tstop", "solder mask"},      {"bstop", "solder mask"},     {"assy", "documentation"},
      {"assembly", "documentation"}, {"fab", "documentation"},     {"doc", "documentation"},
      {"docs", "documentation"},     {"keepout", "documentation"}, {"courtyard", "documentation"},
      {"crtyd", "documentation"},    {"dwgs", "documentation"},    {"cmts", "documentation"}};
  for (const auto& w : kWords)
    if (word == w.first) return w.second;
  return "";
}

// The layer no job cuts that a (lower-case) file name says, by its words or its extension
// (Protel's .gto/.gbo overlay, .gts/.gbs mask, .gtp/.gbp paste); "" when it says none.
std::string other_layer_in_name(const std::string& name) {
  const std::string ext = extension(name);
  if (ext == ".gto" || ext == ".gbo") return "silkscreen";
  if (ext == ".gts" || ext == ".gbs") return "solder mask";
  if (ext == ".gtp" || ext == ".gbp") return "paste";
  // Inner layers: Protel's .g1 .. .g99 and .gp1 .. (planes), KiCad's In1.Cu.
  auto numbered = [](const std::string& w, const std::string& prefix) {
    return w.size() > prefix.size() && w.compare(0, prefix.size(), prefix) == 0 &&
           w.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
  };
  if (numbered(ext, ".g") || numbered(ext, ".gp")) return "inner copper";
  const std::string stem = name.substr(0, name.size() - ext.size());
  std::string word, previous;
  for (size_t i = 0; i <= stem.size(); ++i) {
    if (i < stem.size() && std::isalnum(static_cast<unsigned char>(stem[i])) != 0) {
      word += stem[i];
      continue;
    }
    if (word == "cu" && numbered(previous, "in")) return "inner copper";
    if (!word.empty()) previous = word;
    // A side glued on counts as a word of its own ("TopSilk", "bottompaste", "silktop").
    for (const char* side : {"", "top", "bottom", "bot"}) {
      const std::string t(side);
      const bool front = word.compare(0, t.size(), t) == 0;
      const bool back = ends_with(word, side);
      const char* says = other_layer_word(front ? word.substr(t.size()) : word);
      if (*says == '\0' && back) says = other_layer_word(word.substr(0, word.size() - t.size()));
      if (*says != '\0') return says;
    }
    word.clear();
  }
  return "";
}

bool names_other_layer(const std::string& name) {
  return !other_layer_in_name(name).empty();
}

}  // namespace

namespace {

// The broad table of copper names beyond the extensions: DipTrace (Top.gbr, Bottom.gbr,
// also after '_'), gEDA/pcb (NAME.top.gbr, NAME.bottom.gbr), Allegro/OrCAD (TOP.art,
// BOTTOM.art, ETCH_TOP.art), PADS (art01.pho: layer 1, the top), FAB 3000 (.tl, .bl).
LayerKind copper_from_name_table(const std::string& name, const std::string& ext) {
  if (ext == ".tl") return LayerKind::kCopperTop;
  if (ext == ".bl") return LayerKind::kCopperBottom;
  if (names_other_layer(name)) return LayerKind::kUnknown;
  const std::string stem = name.substr(0, name.size() - ext.size());
  if (ext == ".gbr" || ext == ".art" || ext == ".ger" || ext == ".pho") {
    if (stem == "top" || ends_with(stem, "_top") || ends_with(stem, ".top") ||
        ends_with(stem, "-top") || stem == "toplayer" || stem == "etch_top")
      return LayerKind::kCopperTop;
    if (stem == "bottom" || ends_with(stem, "_bottom") || ends_with(stem, ".bottom") ||
        ends_with(stem, "-bottom") || stem == "bot" || ends_with(stem, "_bot") ||
        stem == "bottomlayer")
      return LayerKind::kCopperBottom;
  }
  if (ext == ".pho" && stem == "art01") return LayerKind::kCopperTop;
  return LayerKind::kUnknown;
}

}  // namespace

LayerKind layer_kind_from_file_name(const std::string& path) {
  const std::string name = base_name(path);
  const std::string ext = extension(name);
  if (ext == ".gtl" || ext == ".cmp" || ext == ".top") return LayerKind::kCopperTop;
  if (ext == ".gbl" || ext == ".sol" || ext == ".bot") return LayerKind::kCopperBottom;
  const LayerKind table = copper_from_name_table(name, ext);
  if (table != LayerKind::kUnknown) return table;
  if (ext == ".gko" || ext == ".gm1" || ext == ".gml" || ext == ".gbr_outline") {
    return LayerKind::kOutline;
  }
  if (ext == ".drl" || ext == ".xln" || ext == ".exc" || ext == ".drd" || ext == ".txt") {
    return ext == ".txt" ? LayerKind::kUnknown : LayerKind::kDrill;
  }
  if (contains(name, "-f.cu.") || contains(name, "-f_cu.") || contains(name, "_f.cu.") ||
      contains(name, "_f_cu.") || contains(name, "copper_top") || contains(name, "toplayer")) {
    return LayerKind::kCopperTop;
  }
  if (contains(name, "-b.cu.") || contains(name, "-b_cu.") || contains(name, "_b.cu.") ||
      contains(name, "_b_cu.") || contains(name, "copper_bottom") ||
      contains(name, "bottomlayer")) {
    return LayerKind::kCopperBottom;
  }
  if (contains(name, "edge.cuts") || contains(name, "edge_cuts") || contains(name, "outline") ||
      contains(name, "profile")) {
    return LayerKind::kOutline;
  }
  return LayerKind::kUnknown;
}

PcbFileFormat pcb_file_format(const std::string& path, const std::string& head_text) {
  if (const size_t bom = utf8_bom_length(head_text))
    return pcb_file_format(path, head_text.substr(bom));
  const std::string ext = extension(base_name(path));
  if (ext == ".gbr" || ext == ".ger" || ext == ".gtl" || ext == ".gbl" || ext == ".gto" ||
      ext == ".gbo" || ext == ".gts" || ext == ".gbs" || ext == ".gko" || ext == ".gm1" ||
      ext == ".gml" || ext == ".gbx" || ext == ".pho" || ext == ".art" || ext == ".cmp" ||
      ext == ".sol" || ext == ".tl" || ext == ".bl") {
    return PcbFileFormat::kGerber;
  }
  // A drill name usually holds Excellon; a Gerber in it is a drill drawing (OrCAD's .drd,
  // gerbv's orcad/rs232_cm.drd; EAGLE's .drd is Excellon), read as what it is. A Gerber may
  // hold kilobytes of G04 comments before its format statement.
  if (ext == ".drl" || ext == ".xln" || ext == ".exc" || ext == ".drd") {
    const size_t first = head_text.find_first_not_of(" \t\r\n");
    const bool gerber = contains(head_text, "%FS") || contains(head_text, "%MOMM") ||
                        contains(head_text, "%MOIN") ||
                        (first != std::string::npos && head_text.compare(first, 3, "G04") == 0);
    return gerber && !starts_like_excellon(head_text) ? PcbFileFormat::kGerber
                                                      : PcbFileFormat::kExcellon;
  }
  if (contains(head_text, "%FS") || contains(head_text, "%MOMM") || contains(head_text, "%MOIN")) {
    return PcbFileFormat::kGerber;
  }
  if (starts_like_excellon(head_text)) {
    return PcbFileFormat::kExcellon;
  }
  return PcbFileFormat::kNone;
}

LayerKind layer_kind_from_file_function(const std::string& value) {
  std::vector<std::string> fields;
  size_t start = 0;
  for (;;) {
    const size_t comma = value.find(',', start);
    std::string f = value.substr(start, comma == std::string::npos ? comma : comma - start);
    const size_t first = f.find_first_not_of(" \t");
    const size_t last = f.find_last_not_of(" \t");
    fields.push_back(first == std::string::npos ? "" : f.substr(first, last - first + 1));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  const std::string& function = fields[0];
  if (function == "Copper") {  // Copper,L<n>,Top|Inr|Bot[,...]
    const std::string side = fields.size() > 2 ? fields[2] : "";
    if (side == "Top") return LayerKind::kCopperTop;
    if (side == "Bot") return LayerKind::kCopperBottom;
    return LayerKind::kUnknown;
  }
  if (function == "Profile") return LayerKind::kOutline;
  if (function == "Plated" || function == "NonPlated") return LayerKind::kDrill;
  return LayerKind::kUnknown;
}

namespace {

// Just after the last non-space character before p (0 at the text's start).
size_t back_over_space(const std::string& text, size_t p) {
  while (p > 0 && std::isspace(static_cast<unsigned char>(text[p - 1]))) --p;
  return p;
}

// A block may start at p: the text's start or the end of another block ('*' or "*%") before
// it, spaces and line ends between.
bool block_starts(const std::string& text, size_t p) {
  p = back_over_space(text, p);
  return p == 0 || text[p - 1] == '*' || text[p - 1] == '%';
}

// The attribute's body starts at `at`: after a block's '%', or after "G04 #@!" (or "G4").
bool attribute_at(const std::string& text, size_t at) {
  const size_t b = back_over_space(text, at);
  if (b > 0 && text[b - 1] == '%') return block_starts(text, b - 1);
  if (b < 3 || text.compare(b - 3, 3, "#@!") != 0) return false;
  const size_t c = back_over_space(text, b - 3);
  if (c >= 3 && text.compare(c - 3, 3, "G04") == 0) return block_starts(text, c - 3);
  return c >= 2 && text.compare(c - 2, 2, "G4") == 0 && block_starts(text, c - 2);
}

}  // namespace

std::string x2_file_function(const std::string& text) {
  for (const std::string key : {"TF.FileFunction,", "TF,.FileFunction,"}) {
    for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
      if (!attribute_at(text, at)) continue;
      const size_t from = at + key.size();
      const size_t end = text.find('*', from);
      return end == std::string::npos ? std::string() : text.substr(from, end - from);
    }
  }
  return std::string();
}

LayerKind layer_kind_from_x2(const std::string& head_text) {
  const std::string function = x2_file_function(head_text);
  return function.empty() ? LayerKind::kUnknown : layer_kind_from_file_function(function);
}

std::string other_layer_from_x2(const std::string& head_text) {
  const std::string function = x2_file_function(head_text);
  const std::string first = function.substr(0, function.find(','));
  if (first.empty() || layer_kind_from_file_function(function) != LayerKind::kUnknown) return "";
  if (first == "Legend") return "silkscreen";
  if (first == "Soldermask") return "solder mask";
  if (first == "Paste") return "paste";
  if (first == "Copper") return "inner copper";
  return "documentation";  // AssemblyDrawing, FabricationDrawing, Component, Other, ...
}

std::string other_layer_from_name(const std::string& path) {
  return other_layer_in_name(base_name(path));
}

PcbFileFormat pcb_file_format(const std::string& path) {
  return pcb_file_format(path, read_file_head(path));
}

}  // namespace host::pcb
