// libFuzzer target: the Gerber RS-274X reader on the input's bytes. Any outcome but a layer
// or a PcbReadError is a finding, as is a layer with a coordinate beyond the reader's
// 10 m limit (plus the largest aperture and step-and-repeat reach).
#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort

#include <string>  // std::string

#include "host/lib/pcb/gerber_reader.h"

namespace {

void check(bool ok) {
  if (!ok) abort();
}

const ClipperLib::cInt kReach = 40000000000LL;  // 40 m in nm

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  host::pcb::GerberOptions options;
  // Keep each run short (2 s under ASan); the limits themselves are exercised.
  options.max_vertices = 200000;
  options.max_reclipped_vertices = 1000000;
  try {
    const host::pcb::PcbLayer l = host::pcb::read_gerber_text(text, "fuzz.gbr", options);
    for (const ClipperLib::Path& p : l.polygons_nm) {
      for (const ClipperLib::IntPoint& q : p) {
        check(q.X > -kReach && q.X < kReach && q.Y > -kReach && q.Y < kReach);
      }
    }
    check(l.units == "mm" || l.units == "inch" || l.polygons_nm.empty());
  } catch (const host::pcb::PcbReadError& e) {
    check(std::string(e.what()).rfind("fuzz.gbr", 0) == 0);
  }
  return 0;
}
