// Chooses the importer from the file's content and extension; refuses formats that are
// not drawings of curves with a message saying what to do instead.
#include <algorithm>   // std::transform
#include <cerrno>      // errno
#include <cstring>     // std::strerror
#include <filesystem>  // std::filesystem::status
#include <fstream>     // std::ifstream
#include <new>         // std::bad_alloc
#include <sstream>     // std::ostringstream

#include "host/lib/drawing/drawing.h"
#include "host/lib/drawing/dxf_import.h"
#include "host/lib/drawing/dxf_scan.h"
#include "host/lib/drawing/file_text.h"  // read_file_head
#include "host/lib/drawing/gcode_import.h"

namespace host {

namespace {

// Lower-case extension with the dot, "" when none.
std::string extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

bool is_gerber(const std::string& ext, const std::string& text) {
  return ext == ".gbr" || ext == ".ger" || ext == ".gtl" || ext == ".gbl" || ext == ".gto" ||
         ext == ".gbo" || ext == ".gts" || ext == ".gbs" || ext == ".gko" || ext == ".gm1" ||
         text.find("%FSLA") != std::string::npos || text.find("%MOMM*%") != std::string::npos ||
         text.find("%MOIN*%") != std::string::npos;
}

bool is_excellon(const std::string& ext, const std::string& text) {
  return ext == ".drl" || ext == ".xln" || ext == ".exc" || starts_like_excellon(text);
}

}  // namespace

bool starts_like_excellon(const std::string& text) {
  size_t i = 0;
  while (i < text.size()) {
    const size_t end = std::min(text.find('\n', i), text.size());
    const size_t a = text.find_first_not_of(" \t\r", i);
    if (a < end && text[a] != ';') {
      const size_t last = text.find_last_not_of(" \t\r", end - 1);
      const std::string line = text.substr(a, last + 1 - a);
      const bool skipped =
          line == "%" || line.compare(0, 4, "INCH") == 0 || line.compare(0, 6, "METRIC") == 0;
      if (!skipped) return line.compare(0, 3, "M48") == 0;
    }
    i = end + 1;
  }
  return false;
}

void check_readable(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found) {
    throw ImportError(path + ": cannot open the file: no such file");
  }
  if (st.type() == std::filesystem::file_type::directory) {
    throw ImportError(path + ": is a directory, not a drawing file");
  }
  // Asked before opening: opening a FIFO waits for a writer (`info f.dxf` hung).
  if (!not_a_file_text(path).empty()) throw ImportError(path + ": " + not_a_file_text(path));
  errno = 0;
  std::ifstream probe(path, std::ios::binary);
  if (!probe) {
    const int why = errno;
    throw ImportError(path + ": cannot open the file: " +
                      (why != 0 ? std::strerror(why) : std::string("unknown reason")));
  }
}

Extents Drawing::extents() const {
  Extents e;
  for (const Curve& c : curves) e.add(curve_extents(c.spline()));
  for (const ProgramOp& op : program)
    if (op.kind == ProgramOp::kDrill) e.add(op.at);
  return e;
}

namespace {

Drawing import_by_format(const std::string& path, const WorkProgress& progress) {
  check_readable(path);
  const std::string ext = extension(path);
  const std::string text = read_file_head(path);
  if (text.empty()) throw ImportError(path + ": the file is empty");
  if (ext == ".dxf" || looks_like_dxf(path)) return import_dxf(path, progress);
  if (is_gerber(ext, text)) {
    throw ImportError(path +
                      ": this is a Gerber (RS-274X) PCB layer, not a drawing of tool paths: "
                      "`engraver board`, `run`, `send` and `points` plan its isolation "
                      "routing (give the board's folder or files).");
  }
  if (is_excellon(ext, text)) {
    throw ImportError(path +
                      ": this is an Excellon drill file (holes, not curves): `engraver board`, "
                      "`run`, `send` and `points` plan its drilling (give the board's folder or "
                      "files).");
  }
  if (ext == ".ngc" || ext == ".nc" || ext == ".gcode" || ext == ".g" || ext == ".tap" ||
      looks_like_gcode(text)) {
    return import_gcode(path);
  }
  throw ImportError(path +
                    ": not a format this tool reads (expected an ASCII DXF drawing, "
                    "or G-code with G0/G1/G2/G3 moves)");
}

}  // namespace

// Only ImportError leaves: anything else an importer lets out is reported as what it is,
// with the file's name (callers map ImportError to "input error").
Drawing import_drawing(const std::string& path) {
  return import_drawing(path, nullptr);
}

Drawing import_drawing(const std::string& path, const WorkProgress& progress) {
  try {
    return import_by_format(path, progress);
  } catch (const std::exception&) {
    rethrow_as_import_error(path, "the drawing");
  }
}

void rethrow_as_import_error(const std::string& path, const std::string& drawing) {
  try {
    throw;
  } catch (const ImportError&) {
    throw;
  } catch (const WorkStopped&) {
    throw;
  } catch (const std::exception& e) {
    // Out of memory is the file's size; a bad array length (a size gone wrong) is a bug.
    if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr &&
        dynamic_cast<const std::bad_array_new_length*>(&e) == nullptr) {
      throw ImportError(path + ": not enough memory to import the drawing");
    }
    throw ImportError(path + ": internal error while importing " + drawing +
                      " (please report): " + e.what());
  }
}

}  // namespace host
