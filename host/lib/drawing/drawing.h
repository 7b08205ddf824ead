// A drawing as imported: its curves as B-splines in millimetres, where each came from,
// the units it declared, the entities it held and the problems found.
#ifndef HOST_LIB_DRAWING_DRAWING_H
#define HOST_LIB_DRAWING_DRAWING_H

#include <map>        // std::map
#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/lib/drawing/bspline.h"

namespace host {

// One curve of the drawing, in the drawing's own frame, converted to mm.
struct Curve {
  BSpline spline;
  std::string source;  // entity it came from, e.g. "SPLINE #3 (handle 2F, layer 0)"
  std::string kind;    // entity type: "SPLINE", "LINE", "ARC", ...
};

struct Drawing {
  std::string path;
  std::string format;       // "DXF", "G-code"
  std::string units;        // "mm", "cm", "m", "inch", or "mm (assumed)"
  double unit_to_mm = 1.0;  // factor applied to every file coordinate
  std::vector<Curve> curves;
  std::map<std::string, int> entity_counts;  // entities read, by DXF type (incl. skipped)
  std::vector<std::string> warnings;         // problems that did not stop the import
  Extents extents() const;
};

// Why a file could not be imported. what() names the file, the entity and the problem.
class ImportError : public std::runtime_error {
 public:
  explicit ImportError(const std::string& msg) : std::runtime_error(msg) {}
};

// Reads a drawing; the format is chosen from the content and the extension (DXF; G-code
// .ngc/.nc/.gcode). Throws ImportError for anything it cannot import faithfully.
Drawing import_drawing(const std::string& path);

}  // namespace host

#endif  // HOST_LIB_DRAWING_DRAWING_H
