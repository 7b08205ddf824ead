// Tokenizer and syntax check of ASCII DXF (see dxf_scan.h).
#include "host/lib/drawing/dxf_scan.h"

#include <algorithm>  // std::min, std::find_if
#include <cerrno>     // errno
#include <climits>    // INT_MAX
#include <cmath>      // std::isfinite
#include <cstdio>     // std::snprintf
#include <cstdlib>    // std::strtod, std::strtoll
#include <fstream>    // std::ifstream
#include <sstream>    // std::ostringstream

#include "host/lib/drawing/drawing.h"
#include "host/lib/drawing/file_text.h"  // not_a_file_text

namespace host {

namespace {

// Group codes whose values are floating point numbers (DXF reference, "group code value
// types").
bool is_real_code(long c) {
  return (c >= 10 && c <= 59) || (c >= 110 && c <= 149) || (c >= 210 && c <= 239) ||
         (c >= 460 && c <= 469) || (c >= 1010 && c <= 1059);
}

// Largest magnitude of an integer group's value by its type (16, 32 or 64 bit); 0 when the
// code's value is not an integer.
long long int_code_limit(long c) {
  // The reference gives 16 bits to 60..79 and others, but writers put larger counts in
  // 72..74; dxflib holds all of them in an int, so an int's range is what must hold.
  if ((c >= 60 && c <= 99) || (c >= 170 && c <= 179) || (c >= 270 && c <= 289) ||
      (c >= 370 && c <= 389) || (c >= 400 && c <= 409) || (c >= 420 && c <= 429) ||
      (c >= 440 && c <= 459) || (c >= 1060 && c <= 1071)) {
    return INT_MAX;
  }
  if (c >= 160 && c <= 169) return LLONG_MAX;
  return 0;
}

// Trims spaces, tabs and CR.
std::string strip(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r\n");
  size_t e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// A decimal number as dxflib's reader understands it: [sign] digits [. digits] [e [sign]
// digits]. Refuses hexadecimal, "inf", "nan" and trailing garbage (strtod alone would take
// some of them).
bool is_decimal_real(const std::string& s) {
  size_t i = 0, digits = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exp_digits = 0;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++exp_digits;
    if (exp_digits == 0) return false;
  }
  return i == s.size();
}

// [sign] digits.
bool is_decimal_int(const std::string& s) {
  size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (i == s.size()) return false;
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
  }
  return true;
}

// Where a problem is: "file: line N, in ENTITY starting at line M (handle H)".
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

// Reads the text line by line ('\n', a trailing '\r' dropped).
class Lines {
 public:
  explicit Lines(const std::string& text) : text_(text) {}
  bool next(std::string& line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    line.assign(text_, pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  long number() const { return number_; }
  size_t pos() const { return pos_; }

 private:
  const std::string& text_;
  size_t pos_ = 0;
  long number_ = 0;
};

// Throws unless `v` is a valid value of group `code`; checks announced counts.
void check_value(long code, const std::string& v, const Where& w, size_t file_bytes, long max_count,
                 PolylineShape& poly) {
  if (is_real_code(code)) {
    errno = 0;
    const double d = is_decimal_real(v) ? std::strtod(v.c_str(), nullptr) : 0.0;
    if (!is_decimal_real(v) || errno == ERANGE || !std::isfinite(d)) {
      std::ostringstream o;
      o << w.describe() << ": group " << code << " value '" << v.substr(0, 40)
        << "' is not a finite number";
      throw ImportError(o.str());
    }
    return;
  }
  const long long limit = int_code_limit(code);
  if (limit == 0) return;
  errno = 0;
  const long long n = is_decimal_int(v) ? std::strtoll(v.c_str(), nullptr, 10) : 0;
  if (!is_decimal_int(v)) {
    std::ostringstream o;
    o << w.describe() << ": group " << code << " value '" << v.substr(0, 40)
      << "' is not an integer";
    throw ImportError(o.str());
  }
  if (errno == ERANGE || n > limit || n < -limit - 1) {
    std::ostringstream o;
    o << w.describe() << ": group " << code << " value " << v.substr(0, 40)
      << " is out of range (a " << (limit == INT_MAX ? 32 : 64) << "-bit integer: " << -limit - 1
      << ".." << limit << ")";
    throw ImportError(o.str());
  }
  // Counts of knots, control points, fit points, vertices: dxflib allocates them.
  const bool spline_count = w.entity == "SPLINE" && code >= 72 && code <= 74;
  const bool vertex_count = w.entity == "LWPOLYLINE" && code == 90;
  const bool leader_count = w.entity == "LEADER" && code == 76;
  if (vertex_count && poly.active) poly.declared = static_cast<long>(n);
  if ((spline_count || vertex_count || leader_count) && (n < 0 || n > max_count)) {
    std::ostringstream o;
    o << w.describe() << ": group " << code << " announces " << n << " items (must be 0.."
      << max_count << ": ";
    if (max_count < kMaxDxfDeclaredCount) {
      o << "a " << file_bytes << "-byte file holds at most one item per " << kMinDxfItemBytes
        << " bytes)";
    } else {
      o << "no drawing needs more)";
    }
    throw ImportError(o.str());
  }
}

// A group code line's number (0..1071), or ImportError naming what stands there: binary data
// (a NUL or another control byte: an executable, an image, a zip named .dxf) said as such.
// `line` is the code line as read, beginning at byte `start` of the file.
long group_code(const std::string& code_text, const std::string& line, size_t start,
                const Where& w) {
  long code = -1;
  if (is_decimal_int(code_text) && code_text.size() <= 6)
    code = std::strtol(code_text.c_str(), nullptr, 10);
  if (code < 0 || code > 1071) {
    const size_t nul = line.find('\0');
    const auto control = std::find_if(line.begin(), line.end(), [](char c) {
      const auto u = static_cast<unsigned char>(c);
      return (u < 0x20 && c != '\t' && c != '\r') || u == 0x7F;
    });
    if (nul != std::string::npos || control != line.end()) {
      const size_t at = nul != std::string::npos ? nul : control - line.begin();
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(line[at]));
      std::ostringstream o;
      o << w.path << ": line " << w.line << ": not a DXF file: binary data ("
        << (nul != std::string::npos ? std::string("a NUL byte") : "byte " + std::string(byte))
        << " at byte " << start + at << ")";
      throw ImportError(o.str());
    }
    std::string shown = code_text.substr(0, 40);
    for (char& c : shown) {
      if (c == '\0') c = '?';
    }
    throw ImportError(w.describe() + ": '" + shown +
                      "' is not a DXF group code (expected an integer 0..1071)");
  }
  return code;
}

// A group's value line (line number `line`) stripped; a text value cut to what dxflib reads,
// a number that long, a NUL byte or another control byte (not tab or CR) refused: DXF writes
// control characters in text as ^J, so a raw one is a damaged or binary file.
std::string group_value(const std::string& value_line, long code, const Where& w, long line) {
  std::string value = strip(value_line);
  const auto control = std::find_if(value.begin(), value.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u < 0x20 && c != '\t' && c != '\r' && c != '\0') || u == 0x7F;
  });
  if (control != value.end() && value.find('\0') == std::string::npos) {
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(*control));
    std::ostringstream o;
    o << w.path << ": line " << line << ", in " << w.entity << ": a control byte (" << byte
      << ") in the value of group " << code << " (binary data in a text file?)";
    throw ImportError(o.str());
  }
  if (value.size() > kMaxDxfValueChars) {
    // dxflib reads lines of at most 1023 characters (a longer one stops its reader).
    if (is_real_code(code) || int_code_limit(code) != 0) {
      std::ostringstream o;
      o << w.path << ": line " << line << ", in " << w.entity << ": the value of group " << code
        << " is " << value.size() << " characters long (a number has at most " << kMaxDxfValueChars
        << ")";
      throw ImportError(o.str());
    }
    value.resize(kMaxDxfValueChars);  // text, names: not engraved
  }
  if (value.find('\0') != std::string::npos) {
    std::ostringstream o;
    o << w.path << ": line " << line << ", in " << w.entity << ": a NUL byte in the value of group "
      << code << " (binary data in a text file?)";
    throw ImportError(o.str());
  }
  return value;
}

// A new record (group 0, or 9: dxflib ends the previous record on a header variable as on
// group 0): the previous LWPOLYLINE's vertex count checked, the place moved on.
void start_record(const std::string& type, Where& w, PolylineShape& poly) {
  if (poly.active && poly.declared != poly.vertices) {
    std::ostringstream o;
    o << w.describe() << ": announces " << poly.declared << " vertices (group 90) but lists "
      << poly.vertices;
    throw ImportError(o.str());
  }
  poly = PolylineShape();
  poly.active = type == "LWPOLYLINE";
  w.entity = type.empty() ? std::string("an unnamed record") : type;
  w.entity_line = w.line;
  w.handle.clear();
}

// Nothing but blanks, NULs and a Ctrl-Z may follow '0 EOF' (at `pos` in the text).
void check_nothing_after_eof(const std::string& text, size_t pos, const Where& w) {
  const size_t rest = text.find_first_not_of(std::string(" \t\r\n\0\x1a", 6), pos);
  if (rest == std::string::npos) return;
  const long after = w.line + 2 +
                     static_cast<long>(std::count(text.begin() + static_cast<long>(pos),
                                                  text.begin() + static_cast<long>(rest), '\n'));
  std::ostringstream o;
  o << w.path << ": line " << after << ": data after the end-of-file marker '0 EOF' of line "
    << w.line << " (a damaged or concatenated file?)";
  throw ImportError(o.str());
}

// An LWPOLYLINE's vertex groups counted (10) and placed (42 after a vertex, both after 90).
void count_vertex_group(long code, const Where& w, PolylineShape& poly) {
  if (!poly.active || (code != 10 && code != 42)) return;
  if (poly.declared < 0) {
    throw ImportError(w.describe() + ": vertex data before the vertex count (group 90)");
  }
  if (code == 10) ++poly.vertices;
  if (code == 42 && poly.vertices == 0) {
    throw ImportError(w.describe() + ": a bulge (group 42) before the first vertex");
  }
}

}  // namespace

bool looks_like_dxf(const std::string& path) {
  if (!not_a_file_text(path).empty()) return false;  // a FIFO's open would wait
  std::ifstream in(path, std::ios::binary);
  std::string a, b;
  if (!std::getline(in, a)) return false;
  if (a.rfind("AutoCAD Binary DXF", 0) == 0) return true;
  if (strip(a) == "999") return true;  // a comment first
  if (!std::getline(in, b)) return false;
  return strip(a) == "0" && strip(b) == "SECTION";
}

struct DxfScanner::State {
  State(const std::string& t, const std::string& p) : text(t), lines(t) { w.path = p; }
  const std::string& text;
  long max_count = 0;
  Where w;
  Lines lines;
  PolylineShape poly;
  bool done = false;  // the closing 0/EOF was returned
  std::string code_line, value_line;
};

DxfScanner::DxfScanner(const std::string& text, const std::string& path)
    : s_(new State(text, path)) {
  if (text.rfind("AutoCAD Binary DXF", 0) == 0) {
    throw ImportError(path + ": binary DXF is not supported; save the drawing as ASCII DXF");
  }
  s_->max_count =
      std::min<long>(kMaxDxfDeclaredCount, static_cast<long>(text.size()) / kMinDxfItemBytes);
}

DxfScanner::~DxfScanner() = default;

bool DxfScanner::next(DxfGroup* group) {
  if (s_->done) return false;
  const std::string& text = s_->text;
  Where& w = s_->w;
  Lines& lines = s_->lines;
  while (lines.next(s_->code_line)) {
    w.line = lines.number();
    const std::string code_text = strip(s_->code_line);
    if (code_text.empty() && lines.pos() >= text.size()) break;  // trailing blank line
    // Lines::next leaves pos() one past the line's end, its '\n' or the end of the text.
    const long code =
        group_code(code_text, s_->code_line, lines.pos() - 1 - s_->code_line.size(), w);
    if (!lines.next(s_->value_line)) {
      throw ImportError(w.describe() + ": the file ends after group code " + code_text +
                        " without its value (truncated file?)");
    }
    const std::string value = group_value(s_->value_line, code, w, lines.number());
    if (code == 999) continue;  // comment: not given to dxflib
    if (code == 0 || code == 9) {
      start_record(value, w, s_->poly);
      *group = DxfGroup{static_cast<int>(code), value, w.line};
      if (code == 0 && value == "EOF") {
        check_nothing_after_eof(text, lines.pos(), w);
        s_->done = true;
      }
      return true;
    }
    if (code == 5) w.handle = value.substr(0, 40);
    count_vertex_group(code, w, s_->poly);
    check_value(code, value, w, text.size(), s_->max_count, s_->poly);
    *group = DxfGroup{static_cast<int>(code), value, w.line};
    return true;
  }
  std::ostringstream o;
  o << w.path << ": the file ends at line " << lines.number() << " inside " << w.entity
    << " without the closing '0 EOF' (truncated file?)";
  throw ImportError(o.str());
}

size_t DxfScanner::pos() const {
  return s_->lines.pos();
}

void check_dxf(const std::string& text, const std::string& path, const WorkProgress& progress) {
  DxfScanner scanner(text, path);
  DxfGroup g;
  for (size_t n = 0; scanner.next(&g); ++n) {
    if (progress && n % 65536 == 0) progress("bytes checked", scanner.pos(), text.size());
  }
  if (progress) progress("bytes checked", text.size(), text.size());
}

}  // namespace host
