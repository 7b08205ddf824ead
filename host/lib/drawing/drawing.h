// A drawing as imported: its curves as B-splines in millimetres, where each came from,
// the units it declared, the entities it held and the problems found.
#ifndef HOST_LIB_DRAWING_DRAWING_H
#define HOST_LIB_DRAWING_DRAWING_H

#include <cstddef>     // size_t
#include <functional>  // std::function
#include <map>         // std::map
#include <stdexcept>   // std::runtime_error
#include <string>      // std::string
#include <utility>     // std::move
#include <vector>      // std::vector

#include "host/lib/drawing/bspline.h"
#include "host/lib/drawing/held_spline.h"

namespace host {

// One curve of the drawing, in the drawing's own frame, converted to mm. A straight line
// is held as its two ends (a million-line drawing: 168 bytes a line, was 288).
struct Curve {
  // The curve, made again from the two ends for a straight line: take it once per use.
  const BSpline spline() const { return held.get(); }
  void set_spline(BSpline s) { held.set(std::move(s)); }

  HeldSpline held;
  std::string source;  // entity it came from, e.g. "SPLINE #3 (handle 2F, layer 0)"
  // Entity type: "SPLINE", "LINE", "ARC", ... (a string literal: 8 bytes a curve, not 32).
  const char* kind = "";
};

// One step of a program whose order matters (G-code from a CAM program): a cut along a
// curve, or a machine action that is not a curve. Units: mm and seconds, drawing frame.
struct ProgramOp {
  enum Kind {
    kCut,      // trace curves[curve] at depth_mm
    kPause,    // M0/M1/M6: wait for the operator; text says why (from "(MSG, ...)" if any)
    kDwell,    // G4: wait dwell_s with every axis still
    kSpindle,  // M3/M4 (spindle_on) or M5
    kDrill     // one hole of a G81/G82/G83 cycle
  };
  Kind kind = kCut;
  int curve = -1;           // kCut: index into Drawing::curves
  double depth_mm = 0.0;    // kCut: Z of the cut (<= 0); NaN: none given (the planner's)
  std::string text;         // kPause: the whole message
  int tool = 0;             // kPause: the tool of an M6 tool change (0: not a tool change)
  double z_mm = 0.0;        // kPause, kDwell, kSpindle: the program's Z here (> 0: out of the work;
                            // for a pause, the tool-change height)
  double dwell_s = 0.0;     // kDwell; kDrill: dwell at the bottom (G82 P)
  bool spindle_on = false;  // kSpindle
  Point2 at{0, 0};          // kDrill: hole centre
  double z_start_mm = 0.0;  // kDrill: R plane, where the feed starts
  double z_bottom_mm = 0.0;  // kDrill: bottom of the hole
  double retract_mm = 0.0;   // kDrill: Z after the hole (R for G99, the start height for G98)
  double peck_mm = 0.0;      // kDrill: G83 peck depth Q (0: one plunge)
  double feed_mm_per_s = 0;  // kDrill: plunge feed from the file (0: none given)
  std::string source;        // where it came from, e.g. "line 23"
};

struct Drawing {
  std::string path;
  std::string format;       // "DXF", "G-code"
  std::string units;        // "mm", "cm", "m", "inch", or "mm (assumed)"
  double unit_to_mm = 1.0;  // factor applied to every file coordinate
  std::vector<Curve> curves;
  std::map<std::string, int> entity_counts;  // entities read, by DXF type (incl. skipped)
  std::vector<std::string> warnings;         // problems that did not stop the import
  // Empty for drawings without an order (DXF): the planner may reorder and reverse curves.
  // Otherwise every curve appears once, as a kCut, and the planner keeps this order.
  std::vector<ProgramOp> program;
  Extents extents() const;  // of the curves and the drilled holes
};

// Why a file could not be imported. what() names the file, the entity and the problem.
class ImportError : public std::runtime_error {
 public:
  explicit ImportError(const std::string& msg) : std::runtime_error(msg) {}
};

// Throws ImportError saying why the file cannot be read: no such file, a directory,
// permission denied (the system's reason), not a regular file.
void check_readable(const std::string& path);

// True when the text starts like an Excellon drill file: M48 on the first line that is not
// blank, a ';' comment, a lone '%' (EAGLE's and Fritzing's drill files start with one) or a
// unit line written before the header (INCH,TZ / METRIC in old EAGLE files). G-code may
// carry an M48 (enable overrides) further down, after its first command.
bool starts_like_excellon(const std::string& text);

// Reads a drawing; the format is chosen from the content and the extension (DXF; G-code
// .ngc/.nc/.gcode). Throws ImportError for anything it cannot import faithfully.
Drawing import_drawing(const std::string& path);

// Called now and then during long work (importing, planning), for a progress bar: what is
// counted ("bytes checked", "curves ordered"), done of total. A new unit starts a new stage.
using WorkProgress = std::function<void(const char* unit, size_t done, size_t total)>;
// What a WorkProgress throws to end the work early (a server that stops, a job aborted while
// it is planned); the importers and the planner let it through as it is.
class WorkStopped : public std::runtime_error {
 public:
  WorkStopped() : std::runtime_error("work stopped") {}
};

// import_drawing, reporting its progress (a DXF: the bytes checked, then read).
Drawing import_drawing(const std::string& path, const WorkProgress& progress);

// In an importer's catch (const std::exception&): ImportError and WorkStopped go on as they
// are; anything else becomes an ImportError naming the file ("not enough memory", or an
// internal error while importing `drawing`, e.g. "the DXF drawing", to report).
[[noreturn]] void rethrow_as_import_error(const std::string& path, const std::string& drawing);

}  // namespace host

#endif  // HOST_LIB_DRAWING_DRAWING_H
