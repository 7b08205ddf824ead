// G-code import (RS-274 / LinuxCNC dialect, as CAM programs such as pcb2gcode and FlatCAM
// write it): G0/G1/G2/G3 in the XY plane become lines and exact arcs, each run of cutting
// moves one curve; dwells, pauses (M0/M1/M6), spindle switching and drilling cycles
// (G81/G82/G83) become program operations, kept in file order (Drawing::program).
#ifndef HOST_LIB_DRAWING_GCODE_IMPORT_H
#define HOST_LIB_DRAWING_GCODE_IMPORT_H

#include <string>  // std::string

#include "host/lib/drawing/drawing.h"

namespace host {

// True when the text reads like G-code (G0/G1/G2/G3 words at line starts).
bool looks_like_gcode(const std::string& text);

// Reads a G-code file. Throws ImportError naming the file, the line and the problem.
Drawing import_gcode(const std::string& path);

// The same on a program already in memory; `name` stands for the file in messages.
Drawing import_gcode_text(const std::string& text, const std::string& name);

}  // namespace host

#endif  // HOST_LIB_DRAWING_GCODE_IMPORT_H
