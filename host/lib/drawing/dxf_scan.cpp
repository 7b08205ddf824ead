// Pre-flight check of the DXF group structure (see dxf_scan.h).
#include "host/lib/drawing/dxf_scan.h"

#include <cerrno>   // errno
#include <cmath>    // std::isfinite
#include <cstdlib>  // std::strtod, std::strtol
#include <fstream>  // std::ifstream
#include <sstream>  // std::ostringstream

#include "host/lib/drawing/drawing.h"

namespace host {

namespace {

// Group codes whose values are floating point numbers (DXF reference, "group code value
// types").
bool is_real_code(long c) {
  return (c >= 10 && c <= 59) || (c >= 110 && c <= 149) || (c >= 210 && c <= 239) ||
         (c >= 460 && c <= 469) || (c >= 1010 && c <= 1059);
}

// Group codes whose values are integers.
bool is_int_code(long c) {
  return (c >= 60 && c <= 99) || (c >= 170 && c <= 179) || (c >= 270 && c <= 289) ||
         (c >= 370 && c <= 389) || (c >= 400 && c <= 409) || (c >= 420 && c <= 429) ||
         (c >= 440 && c <= 459) || (c >= 1060 && c <= 1071);
}

// Trims spaces, tabs and CR (dxflib does the same).
std::string strip(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r\n");
  size_t e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Where a problem is: "file: line N, ENTITY (handle H)".
struct Where {
  std::string path;
  long line = 0;
  std::string entity = "file header";
  long entity_line = 0;
  std::string handle;
  std::string describe() const {
    std::ostringstream o;
    o << path << ": line " << line << ", in " << entity;
    if (entity_line > 0) o << " starting at line " << entity_line;
    if (!handle.empty()) o << " (handle " << handle << ")";
    return o.str();
  }
};

// LWPOLYLINE structure as dxflib needs it: the vertex count (group 90) first, then each
// vertex starting with its x (group 10). dxflib writes a bulge (group 42) that comes before
// the first vertex to index -1 of its vertex array, and silently drops vertices beyond the
// count, so both are refused here.
struct PolylineShape {
  bool active = false;
  long declared = -1;  // group 90
  long vertices = 0;   // groups 10
};

// Largest count a group may announce (control points, knots, vertices): far beyond any
// sane drawing, small enough that dxflib's allocation of it cannot exhaust memory.
const long kMaxDeclaredCount = 1000000;

}  // namespace

bool looks_like_dxf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string a, b;
  if (!std::getline(in, a)) return false;
  if (a.rfind("AutoCAD Binary DXF", 0) == 0) return true;
  if (strip(a) == "999") return true;  // a comment first
  if (!std::getline(in, b)) return false;
  return strip(a) == "0" && strip(b) == "SECTION";
}

void check_dxf_syntax(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImportError(path + ": cannot open the file");
  Where w;
  w.path = path;
  std::string code_line, value_line;
  bool saw_eof = false;
  long pairs = 0;
  PolylineShape poly;
  while (std::getline(in, code_line)) {
    ++w.line;
    if (pairs == 0 && code_line.rfind("AutoCAD Binary DXF", 0) == 0) {
      throw ImportError(path + ": binary DXF is not supported; save the drawing as ASCII DXF");
    }
    const std::string code_text = strip(code_line);
    if (code_text.empty() && in.peek() == EOF) break;  // trailing blank line
    char* end = 0;
    errno = 0;
    const long code = std::strtol(code_text.c_str(), &end, 10);
    if (code_text.empty() || *end != '\0' || errno != 0 || code < 0 || code > 1071) {
      throw ImportError(w.describe() + ": '" + code_text.substr(0, 40) +
                        "' is not a DXF group code (expected an integer 0..1071)");
    }
    if (!std::getline(in, value_line)) {
      throw ImportError(w.describe() + ": the file ends after group code " + code_text +
                        " without its value (truncated file?)");
    }
    ++w.line;
    ++pairs;
    const std::string value = strip(value_line);
    if (code == 0) {
      if (poly.active && poly.declared != poly.vertices) {
        std::ostringstream o;
        o << w.describe() << ": announces " << poly.declared << " vertices (group 90) but lists "
          << poly.vertices;
        throw ImportError(o.str());
      }
      poly = PolylineShape();
      poly.active = value == "LWPOLYLINE";
      w.entity = value;
      w.entity_line = w.line - 1;
      w.handle.clear();
      if (value == "EOF") {
        saw_eof = true;
        break;
      }
      continue;
    }
    if (code == 5) w.handle = value;
    if (poly.active && (code == 10 || code == 42)) {
      if (poly.declared < 0) {
        throw ImportError(w.describe() + ": vertex data before the vertex count (group 90)");
      }
      if (code == 10) ++poly.vertices;
      if (code == 42 && poly.vertices == 0) {
        throw ImportError(w.describe() + ": a bulge (group 42) before the first vertex");
      }
    }
    if (is_real_code(code)) {
      errno = 0;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
        std::ostringstream o;
        o << w.describe() << ": group " << code << " value '" << value.substr(0, 40)
          << "' is not a finite number";
        throw ImportError(o.str());
      }
    } else if (is_int_code(code)) {
      errno = 0;
      const long v = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || errno == ERANGE) {
        std::ostringstream o;
        o << w.describe() << ": group " << code << " value '" << value.substr(0, 40)
          << "' is not an integer";
        throw ImportError(o.str());
      }
      // Counts of knots, control points, fit points, vertices: dxflib allocates them.
      const bool spline_count = w.entity == "SPLINE" && code >= 72 && code <= 74;
      const bool vertex_count = w.entity == "LWPOLYLINE" && code == 90;
      const bool leader_count = w.entity == "LEADER" && code == 76;
      if (vertex_count && poly.active) poly.declared = v;
      if ((spline_count || vertex_count || leader_count) && (v < 0 || v > kMaxDeclaredCount)) {
        std::ostringstream o;
        o << w.describe() << ": group " << code << " announces " << v << " items (must be 0.."
          << kMaxDeclaredCount << ")";
        throw ImportError(o.str());
      }
    }
  }
  if (!saw_eof) {
    std::ostringstream o;
    o << path << ": the file ends at line " << w.line << " inside " << w.entity
      << " without the closing '0 EOF' (truncated file?)";
    throw ImportError(o.str());
  }
}

}  // namespace host
