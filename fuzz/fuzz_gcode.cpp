// libFuzzer target: the G-code importer on the input's bytes; the check is in
// drawing_import_check.h.
#include "fuzz/drawing_import_check.h"
#include "host/lib/drawing/gcode_import.h"  // import_gcode_text

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fuzz::check_drawing_import(host::import_gcode_text, data, size, "fuzz.ngc");
  return 0;
}
