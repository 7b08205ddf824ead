#include "host/lib/pcb/excellon_reader.h"

#include <cctype>   // std::isdigit, std::isspace, std::isalpha
#include <cmath>    // std::fabs, std::llround
#include <cstdlib>  // std::strtod
#include <map>      // std::map
#include <sstream>  // std::istringstream
#include <vector>   // std::vector

namespace host::pcb {

using ClipperLib::cInt;

namespace {

const double kMaxCoordNm = 1e10;  // 10 m
const double kMaxToolNm = 1e8;    // a 100 mm drill is not a drill

enum class Zeros { kUnknown, kLeadingKept, kTrailingKept };

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

// The next line of text from *at: a line ends at LF, CR LF, or a lone CR (old Mac files;
// gerbv's tests end "X01000Y30000\rM30\r\n", which gerbv reads as two lines).
bool next_line(const std::string& text, size_t& at, std::string& line) {
  if (at >= text.size()) return false;
  const size_t end = text.find_first_of("\r\n", at);
  line = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
  at = end == std::string::npos ? text.size() : end + 1;
  if (end != std::string::npos && text[end] == '\r' && at < text.size() && text[at] == '\n') ++at;
  return true;
}

bool starts_with(const std::string& s, const char* p) {
  return s.rfind(p, 0) == 0;
}

bool contains(const std::string& s, const char* p) {
  return s.find(p) != std::string::npos;
}

class ExcellonReader {
 public:
  ExcellonReader(const std::string& text, const std::string& path) : text_(text), path_(path) {}
  PcbLayer read();

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw PcbReadError(path_ + ":" + std::to_string(line_) + ": " + what);
  }
  void note(const std::string& text) const;
  void header_line(const std::string& s);
  void body_line(const std::string& s);
  bool mode_command(const std::string& s);
  bool route_command(const std::string& s);
  void position_line(const std::string& s);
  void comment(const std::string& s);
  void units_line(const std::string& s);
  bool units_command(const std::string& s);
  void set_units(bool metric);
  void holesize_comment(const std::string& s);
  void define_tool(int n, double diameter, double unit_nm);
  bool oversize(int tool) const;
  void add_slot(const PointNm& from, const PointNm& to);
  void tool(const std::string& s, bool in_header);
  double number(const std::string& s, const char* what) const;
  cInt coordinate(const std::string& s) const;
  // Reads X/Y pairs from s (modal: a missing axis keeps its value); true if any was given.
  bool position(const std::string& s, PointNm& p) const;
  void need_tool();

  const std::string& text_;
  std::string path_;
  int line_ = 0;
  bool in_header_ = false;
  bool done_ = false;
  double unit_nm_ = 0;
  std::string units_;
  Zeros zeros_ = Zeros::kUnknown;
  int int_digits_ = 0, dec_digits_ = 0;  // 0: the unit's default
  bool incremental_ = false;
  bool routing_ = false;  // G00/G01 route mode
  bool plunged_ = false;  // M15 .. M16
  std::map<int, cInt> tools_;
  std::map<int, double> pending_tools_;  // diameters given before the units (PADS)
  // A tool larger than 100 mm: its holes and slots are left out and counted.
  struct Oversize {
    double diameter_mm = 0;
    int holes = 0, slots = 0;
    int line = 0;  // where its size was given
  };
  std::map<int, Oversize> oversize_;
  std::string oversize_text() const;
  static std::string oversize_tool_text(int tool, const Oversize& o);
  int left_out() const;  // holes and slots of oversize tools
  void drill_hole(const PointNm& at);
  void repeat_hole(const std::string& s);
  bool drilled_ = false;  // a hole drilled (the one a repeat hole repeats)
  int tool_ = -1;         // none selected (T0 unloads the tool unless the header defines a T0)
  PointNm offset_;        // G93 work zero
  PointNm at_;
  PcbLayer layer_;
  mutable std::vector<std::pair<std::string, std::pair<int, int>>>
      notes_;  // text, first line, count
};

void ExcellonReader::note(const std::string& text) const {
  for (auto& n : notes_) {
    if (n.first == text) {
      ++n.second.second;
      return;
    }
  }
  notes_.push_back({text, {line_, 1}});
}

PcbLayer ExcellonReader::read() {
  size_t at = 0;
  std::string raw;
  bool seen_header = false;
  for (size_t start = at; !done_ && next_line(text_, at, raw); start = at) {
    ++line_;
    // Excellon is printable text: a NUL is binary data (an executable, an image, a zip), and
    // would cut the message that quotes it short, as for Gerber. (NUL padding after M30 is
    // never read.)
    const size_t nul = raw.find('\0');
    if (nul != std::string::npos)
      fail("not an Excellon file: binary data (a NUL byte at byte " + std::to_string(start + nul) +
           ")");
    const std::string s = trim(raw);
    if (s.empty()) continue;
    if (s[0] == ';') {
      comment(s);
      continue;
    }
    if (s == "M48") {
      in_header_ = true;
      seen_header = true;
      continue;
    }
    if (in_header_) {
      if (s == "%" || s == "M95") {
        in_header_ = false;
        continue;
      }
      header_line(s);
    } else {
      if (s == "%") continue;  // rewind stop (old)
      if (units_command(s)) {
        // Old EAGLE .drd: INCH,TZ before M48.
        if (seen_header) note("units '" + s.substr(0, 20) + "' in the body");
        continue;
      }
      body_line(s);
    }
  }
  if (!done_) fail("the file ends without M30 (end of program): it may be cut short");
  if (!pending_tools_.empty() && unit_nm_ == 0)
    fail("tool T" + std::to_string(pending_tools_.begin()->first) +
         " has a diameter but the file never gives its units (METRIC/INCH, M71/M72)");
  if (layer_.holes.empty() && layer_.slots.empty() && !oversize_.empty() && left_out() > 0)
    fail("every hole and slot is of a tool larger than 100 mm, which is not a drill (" +
         oversize_text() + "): nothing is left to drill");
  for (const auto& [tool, o] : oversize_) {
    if (o.holes + o.slots > 0)
      layer_.notes.push_back("line " + std::to_string(o.line) +
                             ": warning: " + oversize_tool_text(tool, o));
  }
  if (!seen_header) note("no M48 header");
  layer_.path = path_;
  layer_.kind = LayerKind::kDrill;
  layer_.units = units_;
  layer_.apertures_or_tools = static_cast<int>(tools_.size());
  for (const auto& n : notes_) {
    std::string s = "line " + std::to_string(n.second.first) + ": " + n.first;
    if (n.second.second > 1) s += " (" + std::to_string(n.second.second) + " times)";
    layer_.notes.push_back(s);
  }
  return layer_;
}

void ExcellonReader::comment(const std::string& s) {
  if (s.find("Holesize") != std::string::npos) {
    holesize_comment(s);
    return;
  }
  // KiCad: ";FORMAT={-:-/ absolute / inch / decimal}" or "{3:3/ absolute / metric /
  // suppress trailing zeros}"; Eagle/Altium: ";FILE_FORMAT=2:4".
  const size_t f = s.find("FORMAT");
  if (f == std::string::npos) return;
  const std::string rest = s.substr(f);
  const size_t colon = rest.find(':');
  if (colon != std::string::npos && colon > 0 &&
      std::isdigit(static_cast<unsigned char>(rest[colon - 1])) && colon + 1 < rest.size() &&
      std::isdigit(static_cast<unsigned char>(rest[colon + 1]))) {
    int_digits_ = rest[colon - 1] - '0';
    dec_digits_ = rest[colon + 1] - '0';
  }
  if (contains(rest, "suppress trailing")) zeros_ = Zeros::kLeadingKept;
  if (contains(rest, "suppress leading")) zeros_ = Zeros::kTrailingKept;
  if (contains(rest, "absolute")) incremental_ = false;
  if (contains(rest, "metric") && unit_nm_ == 0) set_units(true);
  if (contains(rest, "inch") && unit_nm_ == 0) set_units(false);
}

void ExcellonReader::set_units(bool metric) {
  unit_nm_ = metric ? 1e6 : 25.4e6;
  units_ = metric ? "mm" : "inch";
  // Tools the header defined before its unit line (PADS writes them first).
  for (const auto& [n, d] : pending_tools_) define_tool(n, d, unit_nm_);
  if (!pending_tools_.empty()) note("tools defined before the units line");
  pending_tools_.clear();
}

// Allegro: ";T1 Holesize 1. = 13.000000 Tolerance = +2.000000/-2.000000 PLATED MILS
// Quantity = 2": the only place some of its drill files give a tool's size.
void ExcellonReader::holesize_comment(const std::string& s) {
  std::istringstream in(s.substr(1));
  std::string t, word, holesize, eq;
  double value = 0;
  if (!(in >> t >> word >> holesize >> eq >> value) || t.size() < 2 || t[0] != 'T' ||
      word != "Holesize" || eq != "=")
    return;
  const int n = std::atoi(t.c_str() + 1);
  double unit_nm = 0;
  while (in >> word) {
    if (word == "MILS" || word == "MIL") unit_nm = 25400;
    if (word == "MM" || word == "METRIC") unit_nm = 1e6;
    if (word == "INCH" || word == "INCHES") unit_nm = 25.4e6;
  }
  if (n <= 0 || unit_nm == 0) {
    note("hole size comment without a tool number or a unit ignored: '" + s.substr(0, 40) + "'");
    return;
  }
  if (!tools_.count(n) && !oversize_.count(n)) {
    define_tool(n, value, unit_nm);
    note("tool sizes from ';Tn Holesize' comments (Allegro)");
  }
}

void ExcellonReader::define_tool(int n, double diameter, double unit_nm) {
  const double nm = diameter * unit_nm;
  if (!(nm > 0)) fail("tool T" + std::to_string(n) + " diameter must be above 0");
  if (nm > kMaxToolNm) {
    // A routed cut-out is written as one huge "drill" by some programs: leave its holes out,
    // not the whole file.
    oversize_[n] = {nm / 1e6, 0, 0, line_};
    tools_.erase(n);
    return;
  }
  oversize_.erase(n);
  tools_[n] = static_cast<cInt>(std::llround(nm));
}

static std::string count_of(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// "tool T1 (139.7 mm) is larger than 100 mm, not a drill: its 2 holes and 1 slot left out"
std::string ExcellonReader::oversize_tool_text(int tool, const Oversize& o) {
  std::ostringstream mm;
  mm << std::round(o.diameter_mm * 1000) / 1000;
  std::string what = o.holes ? count_of(o.holes, "hole", "holes") : "";
  if (o.slots) what += (what.empty() ? "" : " and ") + count_of(o.slots, "slot", "slots");
  return "tool T" + std::to_string(tool) + " (" + mm.str() +
         " mm) is larger than 100 mm, not a drill: its " + what + " left out";
}

// Every oversize tool that has holes or slots, "; " between them.
std::string ExcellonReader::oversize_text() const {
  std::string text;
  for (const auto& [tool, o] : oversize_) {
    if (o.holes + o.slots == 0) continue;
    text += (text.empty() ? "" : "; ") + oversize_tool_text(tool, o);
  }
  return text;
}

int ExcellonReader::left_out() const {
  int n = 0;
  for (const auto& t : oversize_) n += t.second.holes + t.second.slots;
  return n;
}

// A hole of the current tool at `at` (or one more left out: an oversize tool).
void ExcellonReader::drill_hole(const PointNm& at) {
  need_tool();
  if (oversize(tool_))
    ++oversize_[tool_].holes;
  else
    layer_.holes.push_back({at, tools_[tool_], tool_});
  at_ = at;
  drilled_ = true;
}

// "R<n>X<dx>Y<dy>": the last hole repeated n times, each dx, dy further (Excellon's repeat
// hole; either step may be left out: 0).
void ExcellonReader::repeat_hole(const std::string& s) {
  size_t k = 1;
  while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
  if (k > 6) fail("repeat count in '" + s.substr(0, 30) + "' above 99999");
  // gerbv repeats from wherever the tool is (0, 0 at the start): holes nobody placed.
  if (!drilled_) fail("repeat hole '" + s.substr(0, 30) + "' before any hole to repeat");
  const int n = std::stoi(s.substr(1, k - 1));
  PointNm step;
  const bool incremental = incremental_;
  incremental_ = true;  // the steps are increments, whatever the mode
  position(s.substr(k), step);
  incremental_ = incremental;
  const PointNm from = at_;
  for (int i = 1; i <= n; ++i) drill_hole({from.x + step.x * i, from.y + step.y * i});
  if (std::llabs(at_.x) > kMaxCoordNm || std::llabs(at_.y) > kMaxCoordNm)
    fail("repeated holes beyond 10 m");
}

bool ExcellonReader::oversize(int tool) const {
  return oversize_.count(tool) != 0;
}

void ExcellonReader::add_slot(const PointNm& from, const PointNm& to) {
  if (oversize(tool_))
    ++oversize_[tool_].slots;
  else
    layer_.slots.push_back({from, to, tools_[tool_], tool_});
}

// METRIC/INCH lines and M71/M72 with a zeros field ("M71,TZ", Upverter); true if s was one.
bool ExcellonReader::units_command(const std::string& s) {
  if (starts_with(s, "METRIC") || starts_with(s, "INCH")) {
    units_line(s);
    return true;
  }
  if ((starts_with(s, "M71,") || starts_with(s, "M72,"))) {
    units_line(std::string(s[2] == '1' ? "METRIC" : "INCH") + s.substr(3));
    return true;
  }
  return false;
}

void ExcellonReader::units_line(const std::string& s) {
  // METRIC[,LZ|TZ][,000.000]  INCH[,LZ|TZ][,00.0000]
  set_units(starts_with(s, "METRIC"));
  size_t start = 0;
  int field = 0;
  for (;;) {
    const size_t comma = s.find(',', start);
    const std::string f = trim(s.substr(start, comma - start));
    if (field > 0) {
      if (f == "LZ") {
        zeros_ = Zeros::kLeadingKept;
      } else if (f == "TZ") {
        zeros_ = Zeros::kTrailingKept;
      } else if (!f.empty() && f.find_first_not_of("0.") == std::string::npos) {
        const size_t dot = f.find('.');
        if (dot == std::string::npos) fail("digit format '" + f + "' without '.'");
        int_digits_ = static_cast<int>(dot);
        dec_digits_ = static_cast<int>(f.size() - dot - 1);
      } else {
        fail("unknown field '" + f + "' in '" + s + "'");
      }
    }
    ++field;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
}

void ExcellonReader::tool(const std::string& s, bool in_header) {
  // T<n>[C<diameter>][F..][S..][B..][H..][Z..] in any order after the number.
  size_t k = 1;
  while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
  if (k == 1 || k > 7) fail("bad tool '" + s + "'");
  const int n = std::stoi(s.substr(1, k - 1));
  bool has_diameter = false;
  double diameter = 0;
  while (k < s.size()) {
    const char letter = s[k];
    size_t end = k + 1;
    while (end < s.size() && !std::isalpha(static_cast<unsigned char>(s[end]))) ++end;
    const std::string value = s.substr(k + 1, end - k - 1);
    if (!std::isalpha(static_cast<unsigned char>(letter))) fail("bad tool '" + s + "'");
    if (letter == 'C') {
      diameter = number(value, "tool diameter");
      has_diameter = true;
    } else if (std::string("FSBHZNDIT").find(letter) == std::string::npos) {
      fail("unknown tool parameter '" + std::string(1, letter) + "' in '" + s + "'");
    }
    k = end;
  }
  if (has_diameter) {
    if (!(diameter > 0))
      fail("tool T" + std::to_string(n) + " diameter " + s.substr(s.find('C') + 1) +
           " is not above 0");
    if (unit_nm_ == 0) {
      if (!in_header)
        fail("tool T" + std::to_string(n) + " defined before the units (METRIC/INCH)");
      pending_tools_[n] = diameter;  // converted when the unit line comes
      return;
    }
    define_tool(n, diameter, unit_nm_);
    if (in_header) return;
    note("tool defined in the body");
  }
  if (in_header) return;
  if (pending_tools_.count(n))
    fail("tool T" + std::to_string(n) + " defined before the units (METRIC/INCH), and none came");
  if (n != 0 && !tools_.count(n) && !oversize(n))
    fail("tool T" + std::to_string(n) + " has no diameter (no T" + std::to_string(n) +
         "C... in the header)");
  // T0 with no T0 defined unloads the tool; a defined T0 is a tool like any (EKF's files).
  tool_ = n == 0 && !tools_.count(0) && !oversize(0) ? -1 : n;
}

void ExcellonReader::header_line(const std::string& s) {
  if (units_command(s)) {
    // METRIC/INCH, M71,TZ
  } else if (s[0] == 'T' && s.size() > 1 && std::isdigit(static_cast<unsigned char>(s[1]))) {
    tool(s, true);
  } else if (starts_with(s, "FMAT")) {
    if (s != "FMAT,2") note("'" + s + "': format 1 commands are read like format 2");
  } else if (s == "M71") {
    set_units(true);
  } else if (s == "M72") {
    set_units(false);
  } else if (s == "G90") {
    incremental_ = false;
  } else if (s == "G91" || s == "ICI" || s == "ICI,ON") {
    incremental_ = true;
    note("incremental coordinates");
  } else {
    note("header line '" + s.substr(0, 30) + "' ignored");
  }
}

// A hole before any tool: the only tool defined is the one meant (with a warning); with more,
// which one is not known.
void ExcellonReader::need_tool() {
  if (tool_ >= 0) return;
  if (tools_.size() + oversize_.size() == 1) {
    tool_ = tools_.empty() ? oversize_.begin()->first : tools_.begin()->first;
    note("warning: a hole before any tool is selected: drilled with T" + std::to_string(tool_) +
         ", the only tool defined");
    return;
  }
  std::string defined;
  for (const auto& t : tools_)
    defined += (defined.empty() ? "" : ", ") + ("T" + std::to_string(t.first));
  fail("a hole or slot before any tool is selected (Tn), and " +
       (tools_.empty() ? std::string("no tool is defined")
                       : "the header defines " + std::to_string(tools_.size()) + " (" + defined +
                             "): which one is meant is not known"));
}

// One line after the header: a tool change, a mode, a route move, or a position.
void ExcellonReader::body_line(const std::string& s) {
  if (s[0] == 'T' && s.size() > 1 && std::isdigit(static_cast<unsigned char>(s[1]))) {
    tool(s, false);
  } else if (mode_command(s) || route_command(s)) {
    // done
  } else if (s[0] == 'R' && s.size() > 1 && std::isdigit(static_cast<unsigned char>(s[1]))) {
    repeat_hole(s);
  } else if ((s[0] == 'X' || s[0] == 'Y') && s.find_first_of(" \t") != std::string::npos) {
    // "X-001000 Y030000" (gerbv's test-drill-spaces.exc): gerbv skips the blanks.
    note("warning: blanks inside a coordinate line ignored");
    std::string packed;
    for (char c : s) {
      if (c != ' ' && c != '\t') packed += c;
    }
    position_line(packed);
  } else if (s[0] == 'X' || s[0] == 'Y') {
    position_line(s);
  } else if (starts_with(s, "M47") || starts_with(s, "M45")) {
    note("operator message '" + s.substr(0, 30) + "' ignored");
  } else if (s != "M48") {
    fail("unknown or unsupported command '" + s.substr(0, 30) + "'");
  }
}

// End of program, absolute/incremental, drill mode, units in the body, the work zero (G93);
// true if s was one.
bool ExcellonReader::mode_command(const std::string& s) {
  if (s == "M30" || s == "M00" || s == "M02") {
    done_ = true;
  } else if (s == "G90" || s == "G91") {
    incremental_ = s == "G91";
    if (incremental_) note("G91 incremental coordinates");
  } else if (s == "G05" || s == "G5" || s == "G81") {
    routing_ = false;
    plunged_ = false;
  } else if (s == "M71" || s == "M72") {
    const std::string before = units_;
    set_units(s == "M71");
    if (!before.empty() && before != units_) note(s + " switches units in the body");
  } else if (starts_with(s, "G93")) {
    // Work zero: later absolute coordinates are relative to it (Mentor writes G93X0Y0).
    PointNm zero;
    const bool incremental = incremental_;
    incremental_ = false;
    position(s.substr(3), zero);
    incremental_ = incremental;
    offset_ = zero;
    if (zero.x != 0 || zero.y != 0) note("G93 work zero offset applied");
  } else {
    return false;
  }
  return true;
}

// Route mode: G00 (move), M15 (tool down), G01 (cut a slot), M16/M17 (tool up); true if s was
// one of them.
bool ExcellonReader::route_command(const std::string& s) {
  if (s == "M15") {
    if (!routing_) fail("M15 (tool down) outside route mode (G00)");
    plunged_ = true;
  } else if (starts_with(s, "M16") || starts_with(s, "M17")) {
    // Tool up; Allegro's route files may carry the next position on the same line.
    plunged_ = false;
    if (s.size() > 3 && !position(s.substr(3), at_))
      fail("unexpected '" + s.substr(3, 20) + "' after M16");
  } else if (starts_with(s, "G00") || starts_with(s, "G01")) {
    PointNm p = at_;
    const bool has = position(s.substr(3), p);
    if (starts_with(s, "G00")) {
      routing_ = true;
      plunged_ = false;
    } else {
      if (!routing_) fail("G01 outside route mode (no G00 before it)");
      if (has && plunged_) {
        need_tool();
        add_slot(at_, p);
      }
    }
    at_ = p;
  } else if (starts_with(s, "G02") || starts_with(s, "G03")) {
    fail("routed arcs (" + s.substr(0, 3) + ") are not supported");
  } else {
    return false;
  }
  return true;
}

// "X..Y..": a hole (drill mode), a route move (route mode), or with G85 a slot.
void ExcellonReader::position_line(const std::string& s) {
  const size_t g85 = s.find("G85");
  if (g85 != std::string::npos) {
    PointNm from = at_;
    position(s.substr(0, g85), from);
    PointNm to = from;  // incremental ends are relative to the start
    if (!position(s.substr(g85 + 3), to)) fail("G85 slot without an end point");
    need_tool();
    add_slot(from, to);
    at_ = to;
    return;
  }
  PointNm p = at_;
  position(s, p);
  if (!routing_) {
    drill_hole(p);
    return;
  }
  if (plunged_) {
    need_tool();
    add_slot(at_, p);
  }
  at_ = p;
}

double ExcellonReader::number(const std::string& s, const char* what) const {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    fail(std::string("bad ") + what + " '" + s + "'");
  return v;
}

cInt ExcellonReader::coordinate(const std::string& s) const {
  if (unit_nm_ == 0) fail("coordinates before the units (METRIC/INCH in the header, or M71/M72)");
  double nm = 0;
  if (s.find('.') != std::string::npos) {
    nm = number(s, "coordinate") * unit_nm_;
  } else {
    size_t k = 0;
    bool negative = false;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) negative = s[k++] == '-';
    const std::string digits = s.substr(k);
    if (digits.empty() || digits.size() > 12 ||
        digits.find_first_not_of("0123456789") != std::string::npos) {
      fail("bad coordinate '" + s + "'");
    }
    const bool metric = unit_nm_ == 1e6;
    const int integer = int_digits_ > 0 ? int_digits_ : (metric ? 3 : 2);
    const int decimals = dec_digits_ > 0 ? dec_digits_ : (metric ? 3 : 4);
    int scale = decimals;  // digits after the point
    if (zeros_ == Zeros::kLeadingKept) {
      scale = static_cast<int>(digits.size()) - integer;
    } else if (zeros_ == Zeros::kUnknown && static_cast<int>(digits.size()) != integer + decimals) {
      note("integer coordinates without LZ/TZ: leading zeros taken as omitted (the default)");
    }
    double v = static_cast<double>(std::stoll(digits));
    for (int q = 0; q < scale; ++q) v /= 10;
    for (int q = 0; q > scale; --q) v *= 10;
    nm = (negative ? -v : v) * unit_nm_;
  }
  if (!(std::fabs(nm) <= kMaxCoordNm)) fail("coordinate '" + s + "' is beyond 10 m");
  return static_cast<cInt>(std::llround(nm));
}

bool ExcellonReader::position(const std::string& s, PointNm& p) const {
  bool any = false;
  size_t k = 0;
  while (k < s.size()) {
    const char axis = s[k];
    const size_t end = end_of_number(s, k + 1);
    const std::string value = s.substr(k + 1, end - k - 1);
    if (axis != 'X' && axis != 'Y')
      fail("unexpected '" + std::string(1, axis) + "' in '" + s + "'");
    if (value.empty()) fail("'" + std::string(1, axis) + "' without a value in '" + s + "'");
    const cInt v = coordinate(value);
    cInt& dst = axis == 'X' ? p.x : p.y;
    dst = incremental_ ? dst + v : v + (axis == 'X' ? offset_.x : offset_.y);
    if (dst > kMaxCoordNm || dst < -kMaxCoordNm) fail("position beyond 10 m");
    any = true;
    k = end;
  }
  return any;
}

}  // namespace

PcbLayer read_excellon_text(const std::string& text, const std::string& path) {
  return ExcellonReader(text, path).read();
}

PcbLayer read_excellon_file(const std::string& path) {
  return read_excellon_text(read_pcb_file_text(path), path);
}

}  // namespace host::pcb
