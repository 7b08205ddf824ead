// libFuzzer target: the DXF importer (scan, dxflib, entity conversion, block expansion) on
// the input's bytes. Any outcome but a drawing or an ImportError is a finding; so is an
// ImportError that only reports an unexpected exception, and a drawing with a coordinate
// that is not finite.
#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort

#include <cmath>   // std::isfinite
#include <string>  // std::string

#include "host/lib/drawing/drawing.h"     // Drawing, ImportError
#include "host/lib/drawing/dxf_import.h"  // import_dxf_text

namespace {

void check(bool ok) {
  if (!ok) abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const host::Drawing d = host::import_dxf_text(text, "fuzz.dxf");
    for (const host::Curve& c : d.curves) {
      for (const host::Point2& p : c.spline.control) {
        check(std::isfinite(p.x()) && std::isfinite(p.y()));
      }
    }
    d.extents();
  } catch (const host::ImportError& e) {
    const std::string m = e.what();
    // The importer's wrappers for unexpected exceptions (the file name comes first, so the
    // input's own text cannot forge these).
    check(m.rfind("fuzz.dxf: internal error", 0) != 0);
    check(m.rfind("fuzz.dxf: not enough memory", 0) != 0);
  }
  return 0;
}
