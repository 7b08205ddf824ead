// The Gerber reader's state in parts with one job each: its messages, the coordinate format and
// units, the aperture table, the graphics state, what has been drawn, the open step-and-repeat
// and knockout. Internal to the Gerber reader files.
#ifndef HOST_LIB_PCB_GERBER_READER_STATE_H
#define HOST_LIB_PCB_GERBER_READER_STATE_H

#include <clipper.hpp>  // ClipperLib::Path, Paths

#include <map>            // std::map
#include <set>            // std::set
#include <string>         // std::string
#include <unordered_map>  // std::unordered_map
#include <vector>         // std::vector

#include "host/lib/pcb/gerber_macro.h"

namespace host::pcb::gerber {

// Objects of one polarity, in drawing order.
struct Batch {
  bool dark = true;
  ClipperLib::Paths paths;
  std::vector<size_t> starts;  // where each object (an outer and its holes) begins in paths
};

struct Aperture {
  char type = 'C';          // C R O P, M for a macro, B for a block (%AB)
  double circle_d_nm = 0;   // type C
  ClipperLib::Paths shape;  // around the origin; positive outers, negative holes
  bool has_hole = false;
  std::vector<Batch> block;  // type B: its objects by polarity, around the origin
};

// An aperture block being read (%ABDnn*% .. %AB*%).
struct OpenBlock {
  int number_d = 0;
  size_t batch_start = 0;  // its objects are batches[batch_start ..]
  bool dark = true;        // the polarity before it
};

// Where the reader is (file and line), the notes it collects (a repeated one counted at its
// first line) and the errors it throws.
class GerberDiagnostics {
 public:
  explicit GerberDiagnostics(const std::string& path) : path(path) {}

  [[noreturn]] void fail(const std::string& what) const;
  // A note at the current line; the same text again only counts.
  void note(const std::string& text);
  // A note at a given line, never merged with another.
  void note_at(const std::string& text, int at_line);
  // A decimal number, or an error naming `what`.
  double number(const std::string& s, const char* what) const;
  // "line N: text (k times)" for every note, in order.
  std::vector<std::string> lines() const;

  const std::string path;
  int line = 1;

 private:
  struct Note {
    std::string text;
    int first_line = 0;
    int count = 0;
  };
  std::vector<Note> notes_;
};

// %FS: digits of the coordinates and how they are written.
struct CoordinateFormat {
  bool given = false;
  int x_int = 2, x_dec = 4, y_int = 2, y_dec = 4;
  bool omit_trailing = false;
  bool incremental = false;
};

// %MO (or G70/G71, or the legacy default inch).
struct GerberUnits {
  double nm = 0;     // nanometres per unit; 0 = not yet set
  std::string name;  // "mm" or "inch"

  void set(GerberDiagnostics& diag, double unit_nm, const char* how);
  // No units before the first size: the format's legacy default, inch, with a warning.
  void need(GerberDiagnostics& diag, const std::string& what);
};

// A D code's last %AD: its text ("D10C,1.0") and line.
struct ApertureDefinitionText {
  std::string text;
  int line = 0;
};

struct ApertureTable {
  std::map<int, Aperture> defined;
  std::map<int, std::string> refused;  // D number -> why its definition was refused
  std::unordered_map<std::string, ApertureMacro> macros;
  // A D code defined again differently after it drew: gerbv draws every use with the last
  // definition, so the file is read again with that one from the first (read()).
  std::set<int> used;  // drew (stroke or flash) since its latest definition
  std::map<int, ApertureDefinitionText> last;
  std::set<int> redefined_after_use;
};

struct GraphicsState {
  ClipperLib::IntPoint at{0, 0};
  int aperture = -1;
  int interpolation = 1;  // 1 linear, 2 clockwise, 3 counter-clockwise
  int quadrant = 0;       // 74 single, 75 multi, 0 not given
  int last_d = 0;
  bool dark = true;
  bool region = false;
  ClipperLib::Path contour;
  ClipperLib::Path contour_as_gerbv;  // the same region as gerbv draws it, once an ill-defined
                                      // arc is in it
  bool done = false;                  // M02 read
};

// What has been drawn, and what it cost.
struct GerberDrawing {
  std::vector<Batch> batches;
  size_t vertices = 0;                    // in batches and strokes
  size_t reclipped = 0;                   // copper vertices clipped again by later batches
  std::vector<ClipperLib::Path> strokes;  // centre lines (outline layers)
  std::vector<double> stroke_widths_nm;   // the aperture's width drawing each one
  bool stroke_open = false;               // the last stroke continues at the current point
  int ill_defined_arcs = 0;  // arcs whose start and end radii differ by > kIllDefinedArcNm
  double ill_defined_max_nm = 0;
};

// An open %SR block.
struct StepRepeat {
  bool active = false;
  long x = 1, y = 1;
  long x_saved = 1, y_saved = 1;
  ClipperLib::cInt i = 0, j = 0;
  size_t batch_start = 0, stroke_start = 0;
};

// %KOC/%KOD without a box, open until the next %KO.
struct OpenKnockout {
  bool open = false;
  bool dark = false;
  double border_nm = 0;
  size_t start = 0;  // the first batch of the objects it surrounds
  int line = 0;
};

// The deprecated image parameters in force (%OF/%IO, %IR, %MI, %SF, %AS, %RO, %IP), applied to
// the finished image.
struct ImageParameters {
  ClipperLib::cInt offset_x = 0, offset_y = 0;
  int rotation_deg = 0;  // %IR: 0, 90, 180, 270 counterclockwise about the origin
  bool mirror_a = false, mirror_b = false;  // x -> -x, y -> -y
  bool swap_ab = false;                     // %ASAYBX: x and y swap
  double layer_rotation_deg = 0;            // %RO: any angle, counterclockwise
  double scale_a = 1, scale_b = 1;          // %SF
  bool negative = false;                    // %IPNEG: copper where nothing is drawn
  int negative_line = 0;
  // %IJ: per axis 'L' (lower left) or 'C' (centre), and an offset, as gerbv reads them.
  bool justify = false;
  char justify_a = 'L', justify_b = 'L';
  double justify_offset_a_nm = 0, justify_offset_b_nm = 0;
  int justify_line = 0;
  std::string justify_text;
  // The non-identity ones in force, each the last of its parameter (a later one replaces an
  // earlier, as gerbv reads them): reported as applied at the end.
  struct Transform {
    std::string which;  // "%RO30"
    std::string what;   // "layer rotation"
    int line = 0;
  };
  std::vector<Transform> transforms;
};

}  // namespace host::pcb::gerber

#endif  // HOST_LIB_PCB_GERBER_READER_STATE_H
