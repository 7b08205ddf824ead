// The check both drawing fuzz targets make: the importer on the input's bytes, read in
// memory, must give a drawing with finite coordinates or the importer's own ImportError.
// An ImportError that only wraps an unexpected exception is a finding too (the file name
// comes first, so the input's own text cannot forge one).
#ifndef FUZZ_DRAWING_IMPORT_CHECK_H
#define FUZZ_DRAWING_IMPORT_CHECK_H

#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort

#include <cmath>   // std::isfinite
#include <string>  // std::string

#include "host/lib/drawing/drawing.h"  // Drawing, ImportError

namespace fuzz {

inline void check(bool ok) {
  if (!ok) abort();
}

// import(text, name) is the importer's in-memory entry point.
template <typename Import>
void check_drawing_import(Import import, const uint8_t* data, size_t size,
                          const std::string& name) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const host::Drawing d = import(text, name);
    for (const host::Curve& c : d.curves) {
      c.held.each_control(
          [](const host::Point2& p) { check(std::isfinite(p.x()) && std::isfinite(p.y())); });
    }
    d.extents();
  } catch (const host::ImportError& e) {
    const std::string m = e.what();
    check(m.rfind(name + ": internal error", 0) != 0);
    check(m.rfind(name + ": not enough memory", 0) != 0);
  }
}

}  // namespace fuzz

#endif  // FUZZ_DRAWING_IMPORT_CHECK_H
