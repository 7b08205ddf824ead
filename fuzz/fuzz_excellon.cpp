// libFuzzer target: the Excellon drill reader on the input's bytes. Any outcome but a layer
// or a PcbReadError is a finding, as is a hole or slot with a size that is not positive or
// a position beyond the reader's 10 m limit.
#include <stddef.h>  // size_t
#include <stdint.h>  // uint8_t
#include <stdlib.h>  // abort

#include <string>  // std::string

#include "host/lib/pcb/excellon_reader.h"

namespace {

void check(bool ok) {
  if (!ok) abort();
}

bool on_board(const host::pcb::PointNm& p) {
  const ClipperLib::cInt reach = 10000000000LL;  // 10 m in nm
  return p.x >= -reach && p.x <= reach && p.y >= -reach && p.y <= reach;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const host::pcb::PcbLayer l = host::pcb::read_excellon_text(text, "fuzz.drl");
    for (const host::pcb::Hole& h : l.holes) check(h.diameter_nm > 0 && on_board(h.at));
    for (const host::pcb::Slot& s : l.slots) {
      check(s.diameter_nm > 0 && on_board(s.from) && on_board(s.to));
    }
  } catch (const host::pcb::PcbReadError& e) {
    check(std::string(e.what()).rfind("fuzz.drl", 0) == 0);
  }
  return 0;
}
