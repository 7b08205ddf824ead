// A drawing read for a command, its stages reported on stderr: a large one takes seconds.
#ifndef HOST_CLI_DRAWING_READ_H
#define HOST_CLI_DRAWING_READ_H

#include <string>  // std::string

#include "host/lib/drawing/drawing.h"

namespace host::cli {

// import_drawing with "read: ... bytes checked/read" lines (as planning's stages).
Drawing read_drawing_reporting(const std::string& path);

}  // namespace host::cli

#endif  // HOST_CLI_DRAWING_READ_H
