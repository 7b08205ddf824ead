// libFuzzer target: the G-code importer on the input's bytes (written to a scratch file,
// since the importer reads a path). Any outcome but a drawing or an ImportError is a
// finding, as is a drawing with a coordinate that is not finite.
#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort
#include <unistd.h>  // getpid

#include <cmath>   // std::isfinite
#include <cstdio>  // std::FILE
#include <string>  // std::string

#include "host/lib/drawing/drawing.h"       // Drawing, ImportError
#include "host/lib/drawing/gcode_import.h"  // import_gcode

namespace {

void check(bool ok) {
  if (!ok) abort();
}

// One scratch file per process (libFuzzer's -jobs/-workers run several).
const std::string& scratch_path() {
  static const std::string path = "/tmp/engraver-fuzz-gcode-" + std::to_string(getpid()) + ".ngc";
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::FILE* f = std::fopen(scratch_path().c_str(), "wb");
  check(f != nullptr);
  check(std::fwrite(data, 1, size, f) == size);
  std::fclose(f);
  try {
    const host::Drawing d = host::import_gcode(scratch_path());
    for (const host::Curve& c : d.curves) {
      for (const host::Point2& p : c.spline.control) {
        check(std::isfinite(p.x()) && std::isfinite(p.y()));
      }
    }
    d.extents();
  } catch (const host::ImportError& e) {
    const std::string m = e.what();
    // import_drawing()'s wrapper for unexpected exceptions, should the importer grow one.
    check(m.rfind(scratch_path() + ": internal error", 0) != 0);
  }
  return 0;
}
