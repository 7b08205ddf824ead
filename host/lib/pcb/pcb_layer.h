// What a PCB fabrication file holds once read: copper as polygons, holes and slots, or a board
// outline, in integer nanometres in the file's own frame (Y up, as Gerber and Excellon draw).
// The Gerber and Excellon readers produce it; isolation, drilling and cut-out planning use it.
#ifndef HOST_LIB_PCB_PCB_LAYER_H
#define HOST_LIB_PCB_PCB_LAYER_H

#include <clipper.hpp>  // ClipperLib::Paths, cInt

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

namespace host::pcb {

// Where a layer sits in the board stack-up; from X2 TF.FileFunction, else the file's
// extension, else the command line.
enum class LayerKind { kUnknown, kCopperTop, kCopperBottom, kOutline, kDrill };
const char* layer_kind_name(LayerKind kind);
// "copper_top", "copper_bottom", "outline", "drill" (the server's board.json).
const char* layer_kind_key(LayerKind kind);

struct PointNm {
  ClipperLib::cInt x = 0;
  ClipperLib::cInt y = 0;
};

// One drilled hole.
struct Hole {
  PointNm at;
  ClipperLib::cInt diameter_nm = 0;
  int tool = 0;  // the file's tool number (T1 -> 1)
};

// A routed slot (Excellon G85, or G00/M15/G01/M16): a straight cut of the tool's diameter.
struct Slot {
  PointNm from;
  PointNm to;
  ClipperLib::cInt diameter_nm = 0;
  int tool = 0;
};

struct PcbLayer {
  std::string path;  // the file it came from
  LayerKind kind = LayerKind::kUnknown;
  // Copper (dark minus clear, step-and-repeat applied), as non-overlapping polygons with
  // holes (Clipper orientation: outers positive, holes negative). For an outline layer: the
  // drawn profile strokes as closed or open paths along their centre lines (strokes that meet
  // end to end are joined; a closed one repeats its first point at the end).
  ClipperLib::Paths polygons_nm;
  bool outline_paths_are_open = false;  // outline layer: polygons_nm holds centre lines
  // Outline layer: the width each centre line was drawn with (parallel to polygons_nm; empty
  // when not known). Strokes close a loop where their drawn widths meet, as gerbv shows.
  std::vector<ClipperLib::cInt> outline_widths_nm;
  std::vector<Hole> holes;         // drill layers
  std::vector<Slot> slots;         // drill layers
  std::vector<std::string> notes;  // deprecated forms accepted, attributes read
  double arc_tolerance_nm = 0;     // chord error used where arcs were flattened
  // What the file declared, for `engraver info`.
  std::string units;           // "mm" or "inch"
  int apertures_or_tools = 0;  // apertures (Gerber) or tools (Excellon) defined
};

// A file that cannot be read faithfully. what() names the file, the line and the problem.
class PcbReadError : public std::runtime_error {
 public:
  explicit PcbReadError(const std::string& msg) : std::runtime_error(msg) {}
};

// 3 when text starts with a UTF-8 byte-order mark (a Windows editor's), else 0: no part of
// Gerber or Excellon.
size_t utf8_bom_length(const std::string& text);

// The text of a PCB file, without a UTF-8 byte-order mark; PcbReadError naming it when it
// cannot be opened or read, or is empty.
std::string read_pcb_file_text(const std::string& path);

// Where the number that starts at `from` in a Gerber or Excellon word ends: after its digits,
// signs and decimal point ("X-1.5Y2" from 1: 5).
size_t end_of_number(const std::string& word, size_t from);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_PCB_LAYER_H
