// libFuzzer target: the DXF importer (scan, dxflib, entity conversion, block expansion) on
// the input's bytes; the check is in drawing_import_check.h.
#include "fuzz/drawing_import_check.h"
#include "host/lib/drawing/dxf_import.h"  // import_dxf_text

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fuzz::check_drawing_import(host::import_dxf_text, data, size, "fuzz.dxf");
  return 0;
}
