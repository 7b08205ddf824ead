#include "host/lib/pcb/pcb_layer.h"

#include "host/lib/drawing/file_text.h"  // read_file_text

namespace host::pcb {

const char* layer_kind_name(LayerKind kind) {
  switch (kind) {
    case LayerKind::kCopperTop:
      return "copper top";
    case LayerKind::kCopperBottom:
      return "copper bottom";
    case LayerKind::kOutline:
      return "outline";
    case LayerKind::kDrill:
      return "drill";
    case LayerKind::kUnknown:
      break;
  }
  return "unknown";
}

std::string read_pcb_file_text(const std::string& path) {
  std::string text;
  const FileRead r = read_file_text(path, &text);
  if (r == FileRead::kCannotOpen) throw PcbReadError(path + ": cannot open the file");
  if (r == FileRead::kReadError) throw PcbReadError(path + ": read error");
  if (text.empty()) throw PcbReadError(path + ": the file is empty");
  return text;
}

}  // namespace host::pcb
