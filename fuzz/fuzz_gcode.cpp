// libFuzzer target: the G-code importer on the input's bytes, read in memory. Any outcome but
// a drawing or an ImportError is a finding, as is a drawing with a coordinate that is not
// finite.
#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort

#include <cmath>   // std::isfinite
#include <string>  // std::string

#include "host/lib/drawing/drawing.h"       // Drawing, ImportError
#include "host/lib/drawing/gcode_import.h"  // read_gcode

namespace {

void check(bool ok) {
  if (!ok) abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const host::Drawing d = host::read_gcode(text, "fuzz.ngc");
    for (const host::Curve& c : d.curves) {
      for (const host::Point2& p : c.spline.control) {
        check(std::isfinite(p.x()) && std::isfinite(p.y()));
      }
    }
    d.extents();
  } catch (const host::ImportError& e) {
    const std::string m = e.what();
    // import_drawing()'s wrapper for unexpected exceptions, should the importer grow one.
    check(m.rfind("fuzz.ngc: internal error", 0) != 0);
  }
  return 0;
}
