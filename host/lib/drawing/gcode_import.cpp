// G-code import: a small interpreter of what CAM programs write; see gcode_import.h and
// docs/user-guide.md ("G-code") for what is engraved, what is kept as a program operation
// and what is refused. Within a line, actions follow LinuxCNC's order of execution:
// tool change, spindle, dwell, modes, motion, then stops.
#include "host/lib/drawing/gcode_import.h"

#include <algorithm>  // std::max, std::min
#include <cctype>     // std::isdigit, std::toupper
#include <cmath>      // std::atan2, std::fabs, std::lround
#include <regex>      // std::regex_search
#include <set>        // std::set
#include <sstream>    // std::istringstream, std::ostringstream

#include "host/lib/drawing/conics.h"
#include "host/lib/drawing/file_text.h"  // read_drawing_text
#include "host/lib/drawing/gcode_words.h"

namespace host {

namespace {

const double kPi = 3.14159265358979323846;

// The words of one line, by letter (the last one wins for axis words; G and M are lists).
struct LineWords {
  std::vector<int> g10;  // G numbers times ten (G91.1 -> 911)
  std::vector<int> m;
  bool has[26] = {};
  double val[26] = {};
  bool have(char l) const { return has[l - 'A']; }
  double get(char l) const { return val[l - 'A']; }
};

std::string g_name(int g10) {
  std::ostringstream o;
  o << "G" << g10 / 10;
  if (g10 % 10) o << "." << g10 % 10;
  return o.str();
}

// The units the program selects (G20/G21), and which it used (for the drawing's units).
struct ProgramUnits {
  double to_mm = 1.0;  // of the selected unit
  bool inch_seen = false, mm_seen = false, first_inch = false;

  void select_inch() {
    to_mm = 25.4;
    if (!inch_seen && !mm_seen) first_inch = true;
    inch_seen = true;
  }
  void select_mm() {
    to_mm = 1.0;
    mm_seen = true;
  }
  // The drawing's units and unit_to_mm, with a warning when the program named none.
  void describe(Drawing* dr) const {
    if (inch_seen && mm_seen) {
      dr->units = std::string("inch and mm (G20 and G21 both used; the first is ") +
                  (first_inch ? "inch)" : "mm)");
      dr->unit_to_mm = first_inch ? 25.4 : 1.0;
    } else if (inch_seen) {
      dr->units = "inch";
      dr->unit_to_mm = 25.4;
    } else if (mm_seen) {
      dr->units = "mm";
    } else {
      dr->units = "mm (assumed)";
      dr->warnings.push_back(dr->path + ": no G20/G21: coordinates taken as millimetres");
    }
  }
};

// What the program's words set that holds until a word changes it (besides the units).
struct ModalState {
  bool absolute = true;       // G90 (G91: relative)
  bool arc_absolute = false;  // G90.1
  bool retract_to_r = false;  // G99 (G98 is the default)
  int motion = 0;             // 0 1 2 3, 81 82 83, -1 after G80
  double feed_per_min = 0.0;  // F in file units per minute (converted when used)
  int tool = 0;               // T
};

// A drilling cycle's words, kept from line to line (G81/G82/G83), in file units (P: s).
struct CycleWords {
  double r = 0, z = 0, p = 0, q = 0;
  bool have_r = false, have_z = false;
};

// The cutting moves since the last pen-up: one curve when flushed.
struct CuttingRun {
  std::vector<BulgeVertex> vertices;
  std::string label;  // "from line N"
  double depth_mm = 0.0;
};

class Interpreter {
 public:
  Interpreter(const std::string& path, bool uses_spindle) : uses_spindle_(uses_spindle) {
    dr_.path = path;
    dr_.format = "G-code";
  }

  // Runs one line; false once the program has ended (M2/M30).
  bool line(const std::string& text, long n) {
    n_ = n;
    where_ = dr_.path + ": line " + std::to_string(n);
    const GcodeBlock block = parse_gcode_line(text, where_);
    if (!block.message.empty()) message_ = block.message;
    LineWords w;
    for (const GcodeWord& word : block.words) {
      if (word.letter == 'G') {
        w.g10.push_back(static_cast<int>(std::lround(word.value * 10)));
      } else if (word.letter == 'M') {
        if (word.value != std::floor(word.value)) throw ImportError(where_ + ": M words are whole");
        w.m.push_back(static_cast<int>(word.value));
      } else {
        w.has[word.letter - 'A'] = true;
        w.val[word.letter - 'A'] = word.value;
      }
    }
    check_words(w);
    return execute(w);
  }

  Drawing finish() {
    flush();
    if (!message_.empty()) {
      dr_.warnings.push_back(dr_.path + ": (MSG, " + message_ +
                             ") is not followed by a stop (M0/M1/M6): not shown");
    }
    if (spindle_on_) spindle(false);
    units_.describe(&dr_);
    dr_.entity_counts["G-code path"] = static_cast<int>(dr_.curves.size());
    for (const ProgramOp& op : dr_.program) {
      if (op.kind == ProgramOp::kDrill) ++dr_.entity_counts["hole (G81/G82/G83)"];
      if (op.kind == ProgramOp::kPause) ++dr_.entity_counts["pause (M0/M1/M6)"];
      if (op.kind == ProgramOp::kDwell) ++dr_.entity_counts["dwell (G4)"];
      if (op.kind == ProgramOp::kSpindle) ++dr_.entity_counts["spindle on/off (M3/M4/M5)"];
    }
    return dr_;
  }

 private:
  void check_words(const LineWords& w) {
    for (char l : {'A', 'B', 'C', 'U', 'V', 'W', 'K'}) {
      if (w.have(l) && w.get(l) != 0.0) {
        throw ImportError(where_ + ": word " + std::string(1, l) +
                          " (an axis or arc offset outside the XY plane) is not supported");
      }
    }
    for (char l : {'D', 'E', 'H'}) {
      if (w.have(l)) {
        throw ImportError(where_ + ": word " + std::string(1, l) +
                          " (tool offsets, extruder) is not supported");
      }
    }
    if (w.have('L') && w.get('L') != std::floor(w.get('L'))) {
      throw ImportError(where_ + ": L (repeat count) must be whole");
    }
  }

  // What a line's M words ask for besides the spindle (switched after a tool change).
  struct MCodes {
    bool tool_change = false, stop = false, end = false;
    int stop_code = 0;  // M0 or M1
  };
  MCodes m_codes(const LineWords& w) {
    MCodes c;
    for (int m : w.m) {
      switch (m) {
        case 0:
        case 1:
          c.stop = true;
          c.stop_code = m;
          break;
        case 2:
        case 30:
          c.end = true;
          break;
        case 3:
        case 4:
        case 5:
          break;  // below, after a tool change
        case 6:
          c.tool_change = true;
          break;
        case 7:
        case 8:
          warn_once("coolant", where_ + ": M" + std::to_string(m) +
                                   " (coolant) ignored: the machine has no coolant");
          break;
        case 9:
          break;  // coolant off: nothing to switch
        case 48:
          break;  // overrides enabled: the controller's feed override always is
        case 49:
          warn_once("overrides", where_ +
                                     ": M49 (overrides off) ignored: the operator's feed "
                                     "override stays available");
          break;
        default:
          throw ImportError(where_ + ": M" + std::to_string(m) +
                            " is not supported (M0 M1 M2 M3 M4 M5 M6 M7 M8 M9 M30 M48 M49 are)");
      }
    }
    return c;
  }

  // A line's G words: the modal state they set, and what they ask for on this line.
  struct GCodes {
    int motion = -2;  // a motion word on this line (-2: none, -1: G80)
    bool dwell = false;
  };
  GCodes g_codes(const LineWords& w) {
    GCodes c;
    for (int g : w.g10) {
      switch (g) {
        case 0:
        case 10:
        case 20:
        case 30:
        case 810:
        case 820:
        case 830:
          c.motion = g / 10;
          break;
        case 800:
          c.motion = -1;
          break;
        case 40:
          c.dwell = true;
          break;
        case 200:
          units_.select_inch();
          break;
        case 210:
          units_.select_mm();
          break;
        case 900:
          modal_.absolute = true;
          break;
        case 910:
          modal_.absolute = false;
          break;
        case 901:
          modal_.arc_absolute = true;
          break;
        case 911:
          modal_.arc_absolute = false;
          break;
        case 980:
          modal_.retract_to_r = false;
          break;
        case 990:
          modal_.retract_to_r = true;
          break;
        case 180:
        case 190:
          throw ImportError(where_ + ": " + g_name(g) +
                            " selects an arc plane other than XY; only G17 (XY) is supported");
        case 410:
        case 420:
          throw ImportError(where_ +
                            ": cutter compensation (G41/G42) is not supported; use "
                            "the tool-radius option of this tool instead");
        case 170:  // XY plane
        case 400:  // compensation off
        case 490:  // tool length offset off
        case 540:  // work offset 1
        case 610:  // exact path
        case 611:  // exact stop
        case 640:  // path blending: the controller keeps its own chord tolerance
        case 940:  // units per minute feed
          break;
        default:
          throw ImportError(where_ + ": " + g_name(g) +
                            " is not supported (G0 G1 G2 G3 G4 G17 G20 G21 G40 G49 G54 G61 "
                            "G61.1 G64 G80 G81 G82 G83 G90 G91 G90.1 G91.1 G94 G98 G99 are)");
      }
    }
    return c;
  }

  // G4 P (seconds).
  void dwell(const LineWords& w) {
    if (!w.have('P')) throw ImportError(where_ + ": G4 without P (seconds)");
    if (w.get('P') < 0) throw ImportError(where_ + ": G4 P is negative");
    if (w.get('P') > 0) {
      flush();
      ProgramOp op;
      op.kind = ProgramOp::kDwell;
      op.dwell_s = w.get('P');  // LinuxCNC: P in seconds
      add(op);
    }
  }

  bool execute(const LineWords& w) {
    // F is converted when used (the units may change later).
    if (w.have('F')) modal_.feed_per_min = w.get('F');
    if (w.have('T')) modal_.tool = static_cast<int>(w.get('T'));
    const MCodes mc = m_codes(w);
    if (mc.tool_change) {
      pause(message_.empty() ? "Change tool T" + std::to_string(modal_.tool) : message_,
            modal_.tool);
    }
    for (int m : w.m) {
      if (m == 3 || m == 4) spindle(true);
      if (m == 5) spindle(false);
    }
    const GCodes gc = g_codes(w);
    if (gc.dwell) dwell(w);
    if (gc.motion != -2) modal_.motion = gc.motion;
    const bool axes = w.have('X') || w.have('Y') || w.have('Z');
    if (axes && gc.dwell) throw ImportError(where_ + ": G4 with X/Y/Z words on the same line");
    if (axes) {
      if (modal_.motion == -1) {
        throw ImportError(where_ +
                          ": X/Y/Z with no motion mode (after G80): add G0 or G1 to the line");
      }
      if (modal_.motion >= 81) {
        drill(w);
      } else {
        move(w);
      }
    }
    if (mc.stop) {
      pause(message_.empty() ? (mc.stop_code == 0 ? "Program stop (M0)" : "Optional stop (M1)")
                             : message_);
    }
    if (mc.end) {
      flush();
      if (spindle_on_) spindle(false);
      return false;
    }
    return true;
  }

  // G0/G1/G2/G3 with the axis words of the line.
  void move(const LineWords& w) {
    const double to_mm = units_.to_mm;
    if (w.have('Z')) {
      const double z = modal_.absolute ? w.get('Z') * to_mm : z_ + w.get('Z') * to_mm;
      if (z > 0 || z != z_) flush();  // lifted off the work, or a new depth: a new run
      z_ = z;
      z_given_ = true;
      moved_since_pause_ = true;
    }
    if (!w.have('X') && !w.have('Y')) return;
    moved_since_pause_ = true;
    Point2 target = pos_;
    if (w.have('X'))
      target.x() = modal_.absolute ? w.get('X') * to_mm : pos_.x() + w.get('X') * to_mm;
    if (w.have('Y'))
      target.y() = modal_.absolute ? w.get('Y') * to_mm : pos_.y() + w.get('Y') * to_mm;
    const bool cutting = modal_.motion != 0 && (!uses_spindle_ || spindle_on_) && z_ <= 0;
    if (!cutting) {
      flush();
      pos_ = target;
      return;
    }
    if (run_.vertices.empty()) {
      BulgeVertex v;
      v.p = pos_;
      run_.vertices.push_back(v);
      run_.label = "from line " + std::to_string(n_);
      run_.depth_mm = z_given_ ? z_ : std::nan("");
    }
    if (modal_.motion == 2 || modal_.motion == 3) {
      arc(w, target);
    } else {
      BulgeVertex v;
      v.p = target;
      run_.vertices.push_back(v);
    }
    pos_ = target;
  }

  void arc(const LineWords& w, const Point2& target) {
    Point2 centre;
    if (w.have('R')) {
      // Radius form: centre on the chord's bisector; R < 0 means the long way round.
      const double rv = w.get('R');
      const Point2 chord = target - pos_;
      const double c = chord.norm();
      const double r = std::fabs(rv) * units_.to_mm;
      if (c < 1e-9) throw ImportError(where_ + ": R-form arc with coinciding ends");
      if (c > 2 * r + 1e-6)
        throw ImportError(where_ + ": arc radius R is shorter than half the chord");
      const double h = std::sqrt(std::max(0.0, r * r - c * c / 4));
      const Point2 left(-chord.y() / c, chord.x() / c);
      // G2 with R > 0: centre right of the chord; G3 with R > 0: left.
      const double side = (modal_.motion == 3 ? 1.0 : -1.0) * (rv < 0 ? -1.0 : 1.0);
      centre = 0.5 * (pos_ + target) + left * (h * side);
    } else {
      if (!w.have('I') && !w.have('J')) throw ImportError(where_ + ": arc without I/J or R");
      const Point2 ij(w.get('I') * units_.to_mm, w.get('J') * units_.to_mm);
      centre = modal_.arc_absolute ? ij : Point2(pos_ + ij);
    }
    const double r0 = (pos_ - centre).norm();
    const double r1 = (target - centre).norm();
    if (std::fabs(r0 - r1) > 0.002 + 0.001 * r0) {
      std::ostringstream o;
      o << where_ << ": arc end is not on the circle (radius " << r0 << " mm at the start, " << r1
        << " mm at the end)";
      throw ImportError(o.str());
    }
    const double a0 = std::atan2(pos_.y() - centre.y(), pos_.x() - centre.x());
    const double a1 = std::atan2(target.y() - centre.y(), target.x() - centre.x());
    double sweep = a1 - a0;
    if (modal_.motion == 3) {
      while (sweep <= 1e-12) sweep += 2 * kPi;
    } else {
      while (sweep >= -1e-12) sweep -= 2 * kPi;
    }
    // At most half a turn per polyline segment (a bulge cannot describe more).
    const int parts = std::fabs(sweep) > kPi - 1e-9 ? 2 : 1;
    for (int k = 1; k <= parts; ++k) {
      run_.vertices.back().bulge = std::tan(sweep / parts / 4);
      BulgeVertex v;
      const double a = a0 + sweep * k / parts;
      v.p = k == parts ? target : Point2(centre + r0 * Point2(std::cos(a), std::sin(a)));
      run_.vertices.push_back(v);
    }
  }

  // One line of a G81/G82/G83 cycle: L holes (L > 1 only makes sense in G91).
  void drill(const LineWords& w) {
    flush();
    moved_since_pause_ = true;
    const int cycle = modal_.motion;
    const double to_mm = units_.to_mm;
    if (w.have('R')) cycle_.r = w.get('R'), cycle_.have_r = true;
    if (w.have('Z')) cycle_.z = w.get('Z'), cycle_.have_z = true;
    if (w.have('P')) cycle_.p = w.get('P');
    if (w.have('Q')) cycle_.q = w.get('Q');
    if (!cycle_.have_r || !cycle_.have_z) {
      throw ImportError(where_ + ": G" + std::to_string(cycle) + " needs R and Z (given on this " +
                        "line or earlier in the cycle)");
    }
    if (cycle == 82 && cycle_.p < 0) throw ImportError(where_ + ": G82 P (dwell) is negative");
    if (cycle == 83 && !(cycle_.q > 0)) throw ImportError(where_ + ": G83 needs Q > 0 (peck)");
    const int repeats = w.have('L') ? static_cast<int>(w.get('L')) : 1;
    if (repeats < 1 || repeats > 10000) throw ImportError(where_ + ": L must be 1..10000");
    for (int k = 0; k < repeats; ++k) {
      const double start_z = z_;
      Point2 at = pos_;
      double r_mm, bottom_mm;
      if (modal_.absolute) {
        if (w.have('X')) at.x() = w.get('X') * to_mm;
        if (w.have('Y')) at.y() = w.get('Y') * to_mm;
        r_mm = cycle_.r * to_mm;
        bottom_mm = cycle_.z * to_mm;
      } else {
        // G91: X/Y from the current point, R from the start height, Z from R.
        at +=
            Point2((w.have('X') ? w.get('X') : 0) * to_mm, (w.have('Y') ? w.get('Y') : 0) * to_mm);
        r_mm = start_z + cycle_.r * to_mm;
        bottom_mm = r_mm + cycle_.z * to_mm;
      }
      if (bottom_mm > r_mm) {
        std::ostringstream o;
        o << where_ << ": G" << cycle << " bottom Z " << bottom_mm << " mm is above R " << r_mm
          << " mm";
        throw ImportError(o.str());
      }
      ProgramOp op;
      op.kind = ProgramOp::kDrill;
      op.at = at;
      op.z_start_mm = r_mm;
      op.z_bottom_mm = bottom_mm;
      // G98 goes back to the height before the cycle unless that is below R.
      op.retract_mm = modal_.retract_to_r ? r_mm : std::max(r_mm, start_z);
      op.dwell_s = cycle == 82 ? cycle_.p : 0.0;
      op.peck_mm = cycle == 83 ? cycle_.q * to_mm : 0.0;
      op.feed_mm_per_s = modal_.feed_per_min * to_mm / 60.0;
      add(op);
      pos_ = at;
      z_ = op.retract_mm;
      z_given_ = true;
    }
  }

  void pause(const std::string& text, int tool = 0) {
    flush();
    const bool told = !message_.empty();  // text is the program's own message
    message_.clear();
    // M6 then M0 with nothing in between (pcb2gcode, FlatCAM): one stop for the operator,
    // with the program's message if either had one.
    if (!dr_.program.empty() && dr_.program.back().kind == ProgramOp::kPause &&
        !moved_since_pause_) {
      ProgramOp& last = dr_.program.back();
      if (tool != 0) last.tool = tool;
      if (told) {
        last.text = last_pause_told_ ? last.text + "; " + text : text;
        last_pause_told_ = true;
      }
      return;
    }
    last_pause_told_ = told;
    ProgramOp op;
    op.kind = ProgramOp::kPause;
    op.text = text;
    op.tool = tool;
    add(op);
    moved_since_pause_ = false;
  }

  void spindle(bool on) {
    if (on == spindle_on_ && spindle_known_) return;
    flush();
    spindle_on_ = on;
    spindle_known_ = true;
    ProgramOp op;
    op.kind = ProgramOp::kSpindle;
    op.spindle_on = on;
    add(op);
  }

  void add(ProgramOp op) {
    op.source = "line " + std::to_string(n_);
    if (op.kind != ProgramOp::kDrill) op.z_mm = z_;
    dr_.program.push_back(op);
  }

  void warn_once(const std::string& key, const std::string& text) {
    if (warned_.insert(key).second) dr_.warnings.push_back(text);
  }

  // Ends the current run of cutting moves: it becomes a curve and a kCut operation.
  void flush() {
    if (run_.vertices.size() >= 2) {
      BSpline s = polyline_spline(run_.vertices, false);
      if (!s.control.empty()) {
        Curve c;
        c.set_spline(s);
        c.kind = "G-code path";
        c.source = "path #" + std::to_string(dr_.curves.size() + 1) + " (" + run_.label + ")";
        dr_.curves.push_back(c);
        ProgramOp op;
        op.kind = ProgramOp::kCut;
        op.curve = static_cast<int>(dr_.curves.size()) - 1;
        op.depth_mm = run_.depth_mm;
        op.source = run_.label.substr(5);  // "line N"
        dr_.program.push_back(op);
        moved_since_pause_ = true;
      }
    }
    run_.vertices.clear();
  }

  Drawing dr_;
  const bool uses_spindle_;
  long n_ = 0;
  std::string where_;
  std::string message_;  // "(MSG, ...)" waiting for the next pause
  ProgramUnits units_;
  ModalState modal_;
  bool spindle_on_ = false, spindle_known_ = false;
  Point2 pos_{0, 0};
  double z_ = 0.0;
  bool z_given_ = false;  // no Z word yet: cuts take the planner's depth
  CycleWords cycle_;
  bool moved_since_pause_ = true;
  bool last_pause_told_ = false;  // the last pause shows the program's message
  CuttingRun run_;
  std::set<std::string> warned_;
};

}  // namespace

bool looks_like_gcode(const std::string& text) {
  static const std::regex re("(^|\\n)\\s*(N\\d+\\s*)?G0?[0-3](\\D|$)", std::regex::icase);
  return std::regex_search(text, re);
}

namespace {

// True when the line's code (before any comment) switches a spindle or laser on: an M3 or M4
// word, leading zeros allowed, not part of a longer number.
bool switches_spindle_on(const std::string& line) {
  const size_t end = std::min(line.find_first_of("(;"), line.size());
  for (size_t i = 0; i < end; ++i) {
    if (std::toupper(static_cast<unsigned char>(line[i])) != 'M') continue;
    if (i > 0 && (std::isdigit(static_cast<unsigned char>(line[i - 1])) || line[i - 1] == '.')) {
      continue;
    }
    size_t k = i + 1;
    while (k < end && line[k] == '0') ++k;
    if (k < end && (line[k] == '3' || line[k] == '4') &&
        (k + 1 == end || !std::isdigit(static_cast<unsigned char>(line[k + 1])))) {
      return true;
    }
  }
  return false;
}

}  // namespace

Drawing import_gcode_text(const std::string& text, const std::string& name) {
  // First pass: does the program switch a spindle or laser at all (M3/M4)? Then only the
  // moves while it is on cut.
  bool uses_spindle = false;
  {
    std::istringstream scan(text);
    std::string l;
    while (!uses_spindle && std::getline(scan, l)) uses_spindle = switches_spindle_on(l);
  }
  Interpreter interp(name, uses_spindle);
  std::istringstream in(text);
  std::string line;
  long n = 0;
  size_t start = 0;  // of the line, in the text
  while (std::getline(in, line)) {
    ++n;
    // G-code is text: a NUL is binary data (an executable, an image named .ngc), said as such
    // as for DXF, Gerber and Excellon (it was "unexpected '\x7F'"). After the program's end
    // (M2, M30) nothing is read.
    const size_t nul = line.find('\0');
    if (nul != std::string::npos) {
      throw ImportError(name + ": line " + std::to_string(n) +
                        ": not a G-code file: binary data (a NUL byte at byte " +
                        std::to_string(start + nul) + ")");
    }
    if (!interp.line(line, n)) break;
    start += line.size() + 1;
  }
  return interp.finish();
}

Drawing import_gcode(const std::string& path) {
  return import_gcode_text(read_drawing_text(path), path);
}

}  // namespace host
