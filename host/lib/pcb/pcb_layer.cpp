#include "host/lib/pcb/pcb_layer.h"

#include <cctype>  // std::isdigit

#include "host/lib/drawing/file_text.h"  // read_text_or_throw

namespace host::pcb {

namespace {

// Each kind's name in messages and its key in the server's board.json.
struct KindNames {
  LayerKind kind;
  const char* name;
  const char* key;
};
const KindNames kKindNames[] = {{LayerKind::kCopperTop, "copper top", "copper_top"},
                                {LayerKind::kCopperBottom, "copper bottom", "copper_bottom"},
                                {LayerKind::kOutline, "outline", "outline"},
                                {LayerKind::kDrill, "drill", "drill"},
                                {LayerKind::kUnknown, "unknown", "unknown"}};

const KindNames& names_of(LayerKind kind) {
  for (const KindNames& k : kKindNames)
    if (k.kind == kind) return k;
  return kKindNames[sizeof(kKindNames) / sizeof(kKindNames[0]) - 1];
}

}  // namespace

const char* layer_kind_name(LayerKind kind) {
  return names_of(kind).name;
}

const char* layer_kind_key(LayerKind kind) {
  return names_of(kind).key;
}

size_t end_of_number(const std::string& word, size_t from) {
  size_t end = from;
  while (end < word.size() && (std::isdigit(static_cast<unsigned char>(word[end])) ||
                               word[end] == '+' || word[end] == '-' || word[end] == '.'))
    ++end;
  return end;
}

size_t utf8_bom_length(const std::string& text) {
  return text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
}

std::string read_pcb_file_text(const std::string& path) {
  std::string text = read_text_or_throw<PcbReadError>(path);
  text.erase(0, utf8_bom_length(text));
  if (text.empty()) throw PcbReadError(path + ": the file is empty");
  return text;
}

}  // namespace host::pcb
