#include "host/lib/pcb/pcb_layer.h"

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

}  // namespace host::pcb
