#include "host/cli/drawing_read.h"

#include <iostream>  // std::cerr

#include "host/lib/progress/progress_meter.h"

namespace host::cli {

Drawing read_drawing_reporting(const std::string& path) {
  StagedProgress read("read", std::cerr, ProgressMeter::for_stderr());
  return import_drawing(path, [&read](const char* unit, size_t done, size_t total) {
    read.update(unit, done, total);
  });
}

}  // namespace host::cli
