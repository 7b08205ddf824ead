// G-code import: a small interpreter for the motion words; see gcode_import.h and
// docs/user-guide.md ("G-code") for what is engraved and what is refused.
#include "host/lib/drawing/gcode_import.h"

#include <cctype>   // std::isalpha, std::toupper
#include <cmath>    // std::atan2, std::fabs
#include <cstdlib>  // std::strtod
#include <fstream>  // std::ifstream
#include <regex>    // std::regex_search
#include <sstream>  // std::ostringstream

#include "host/lib/drawing/conics.h"

namespace host {

namespace {

const double kPi = 3.14159265358979323846;

struct Word {
  char letter;
  double value;
};

// Words of one line, comments "( )" and ";" removed. Throws on a malformed word.
std::vector<Word> parse_line(const std::string& raw, const std::string& where) {
  std::vector<Word> words;
  size_t i = 0;
  while (i < raw.size()) {
    const char c = raw[i];
    if (c == ';') break;
    if (c == '(') {
      const size_t close = raw.find(')', i);
      if (close == std::string::npos) throw ImportError(where + ": comment '(' is not closed");
      i = close + 1;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c)) || c == '%') {
      ++i;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) {
      throw ImportError(where + ": unexpected '" + std::string(1, c) + "'");
    }
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    ++i;
    while (i < raw.size() && raw[i] == ' ') ++i;
    const char* start = raw.c_str() + i;
    char* end = 0;
    const double v = std::strtod(start, &end);
    if (end == start || !std::isfinite(v)) {
      throw ImportError(where + ": word " + std::string(1, letter) + " has no valid number");
    }
    i += static_cast<size_t>(end - start);
    if (std::fabs(v) > 1e7) {
      throw ImportError(where + ": word " + std::string(1, letter) + " value is beyond 10^7");
    }
    words.push_back(Word{letter, v});
  }
  return words;
}

// Interpreter state.
struct State {
  double to_mm = 1.0;
  bool absolute = true;
  bool arc_absolute = false;  // G90.1
  int motion = 0;             // 0 1 2 3
  bool spindle_on = false;
  Point2 pos{0, 0};
  double z = 0.0;
};

}  // namespace

bool looks_like_gcode(const std::string& text) {
  static const std::regex re("(^|\\n)\\s*(N\\d+\\s*)?G0?[0-3](\\D|$)", std::regex::icase);
  return std::regex_search(text, re);
}

Drawing import_gcode(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ImportError(path + ": cannot open the file");
  Drawing dr;
  dr.path = path;
  dr.format = "G-code";
  dr.units = "mm";
  State st;
  bool uses_spindle = false;
  bool units_seen = false;
  {
    // First pass: does the program switch a spindle or laser at all (M3/M4)?
    std::string l;
    std::ifstream scan(path);
    static const std::regex m34("(^|[^0-9.])M0?[34](\\D|$)", std::regex::icase);
    while (std::getline(scan, l)) {
      const std::string code = l.substr(0, l.find_first_of("(;"));
      if (std::regex_search(code, m34)) uses_spindle = true;
    }
  }
  std::vector<BulgeVertex> run;  // the cutting moves since the last pen-up
  std::string run_label;
  int run_count = 0;
  auto flush = [&]() {
    if (run.size() >= 2) {
      BSpline s = polyline_spline(run, false);
      if (!s.control.empty()) {
        Curve c;
        c.spline = s;
        c.kind = "G-code path";
        c.source = "path #" + std::to_string(++run_count) + " (" + run_label + ")";
        dr.curves.push_back(c);
      }
    }
    run.clear();
  };
  std::string line;
  long n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::string where = path + ": line " + std::to_string(n);
    const std::vector<Word> words = parse_line(line, where);
    bool have_x = false, have_y = false, have_z = false, have_i = false, have_j = false,
         have_r = false;
    double x = 0, y = 0, zv = 0, iv = 0, jv = 0, rv = 0;
    bool motion_word = false;
    for (const Word& w : words) {
      const double v = w.value;
      switch (w.letter) {
        case 'G': {
          const int g10 = static_cast<int>(std::lround(v * 10));
          if (g10 == 0 || g10 == 10 || g10 == 20 || g10 == 30) {
            st.motion = g10 / 10;
            motion_word = true;
          } else if (g10 == 200) {
            st.to_mm = 25.4;
            units_seen = true;
          } else if (g10 == 210) {
            st.to_mm = 1.0;
            units_seen = true;
          } else if (g10 == 900) {
            st.absolute = true;
          } else if (g10 == 910) {
            st.absolute = false;
          } else if (g10 == 901) {
            st.arc_absolute = true;
          } else if (g10 == 911) {
            st.arc_absolute = false;
          } else if (g10 == 180 || g10 == 190) {
            throw ImportError(where + ": G" + std::to_string(g10 / 10) +
                              " selects an arc plane other than XY; only G17 (XY) is supported");
          } else if (g10 == 410 || g10 == 420) {
            throw ImportError(where +
                              ": cutter compensation (G41/G42) is not supported; use "
                              "the tool-radius option of this tool instead");
          } else if (g10 == 170 || g10 == 400 || g10 == 940 || g10 == 640 || g10 == 610 ||
                     g10 == 800 || g10 == 540 || g10 == 490) {
            // plane XY, compensation off, feed mode, path mode, cycle off, work offset 1:
            // nothing to do.
          } else {
            std::ostringstream o;
            o << where << ": G" << v << " is not supported (G0 G1 G2 G3 G17 G20 G21 G40 G90 "
              << "G91 G90.1 G91.1 are)";
            throw ImportError(o.str());
          }
          break;
        }
        case 'M': {
          const int m = static_cast<int>(std::lround(v));
          if (m == 3 || m == 4) st.spindle_on = true;
          if (m == 5 || m == 2 || m == 30) st.spindle_on = false;
          if (m == 5 || m == 2 || m == 30) flush();
          break;
        }
        case 'X':
          x = v;
          have_x = true;
          break;
        case 'Y':
          y = v;
          have_y = true;
          break;
        case 'Z':
          zv = v;
          have_z = true;
          break;
        case 'I':
          iv = v;
          have_i = true;
          break;
        case 'J':
          jv = v;
          have_j = true;
          break;
        case 'R':
          rv = v;
          have_r = true;
          break;
        case 'K':
        case 'A':
        case 'B':
        case 'C':
        case 'U':
        case 'V':
        case 'W':
          if (v != 0.0) {
            throw ImportError(where + ": word " + std::string(1, w.letter) +
                              " (an axis or arc offset outside the XY plane) is not supported");
          }
          break;
        default:
          break;  // F S T N P: feed, speed, tool, line number, dwell
      }
    }
    (void)motion_word;
    if (have_z) {
      st.z = st.absolute ? zv * st.to_mm : st.z + zv * st.to_mm;
      if (st.z > 0) flush();  // tool lifted off the work
    }
    if (!have_x && !have_y) continue;
    Point2 target = st.pos;
    if (have_x) target.x() = st.absolute ? x * st.to_mm : st.pos.x() + x * st.to_mm;
    if (have_y) target.y() = st.absolute ? y * st.to_mm : st.pos.y() + y * st.to_mm;
    const bool cutting = st.motion != 0 && (!uses_spindle || st.spindle_on) && st.z <= 0;
    if (!cutting) {
      flush();
      st.pos = target;
      continue;
    }
    if (run.empty()) {
      BulgeVertex v;
      v.p = st.pos;
      run.push_back(v);
      run_label = "from line " + std::to_string(n);
    }
    if (st.motion == 2 || st.motion == 3) {
      Point2 centre;
      if (have_r) {
        // Radius form: centre on the chord's bisector; R < 0 means the long way round.
        const Point2 chord = target - st.pos;
        const double c = chord.norm();
        const double r = std::fabs(rv) * st.to_mm;
        if (c < 1e-9) throw ImportError(where + ": R-form arc with coinciding ends");
        if (c > 2 * r + 1e-6)
          throw ImportError(where + ": arc radius R is shorter than half the chord");
        const double h = std::sqrt(std::max(0.0, r * r - c * c / 4));
        const Point2 left(-chord.y() / c, chord.x() / c);
        // G2 with R > 0: centre right of the chord; G3 with R > 0: left.
        double side = (st.motion == 3 ? 1.0 : -1.0) * (rv < 0 ? -1.0 : 1.0);
        centre = 0.5 * (st.pos + target) + left * (h * side);
      } else {
        if (!have_i && !have_j) throw ImportError(where + ": arc without I/J or R");
        const Point2 ij(iv * st.to_mm, jv * st.to_mm);
        centre = st.arc_absolute ? ij : Point2(st.pos + ij);
      }
      const double r0 = (st.pos - centre).norm();
      const double r1 = (target - centre).norm();
      if (std::fabs(r0 - r1) > 0.002 + 0.001 * r0) {
        std::ostringstream o;
        o << where << ": arc end is not on the circle (radius " << r0 << " mm at the start, " << r1
          << " mm at the end)";
        throw ImportError(o.str());
      }
      const double a0 = std::atan2(st.pos.y() - centre.y(), st.pos.x() - centre.x());
      const double a1 = std::atan2(target.y() - centre.y(), target.x() - centre.x());
      double sweep = a1 - a0;
      if (st.motion == 3) {
        while (sweep <= 1e-12) sweep += 2 * kPi;
      } else {
        while (sweep >= -1e-12) sweep -= 2 * kPi;
      }
      // At most half a turn per polyline segment (a bulge cannot describe more).
      const int parts = std::fabs(sweep) > kPi - 1e-9 ? 2 : 1;
      for (int k = 1; k <= parts; ++k) {
        run.back().bulge = std::tan(sweep / parts / 4);
        BulgeVertex v;
        const double a = a0 + sweep * k / parts;
        v.p = k == parts ? target : Point2(centre + r0 * Point2(std::cos(a), std::sin(a)));
        run.push_back(v);
      }
    } else {
      BulgeVertex v;
      v.p = target;
      run.push_back(v);
    }
    st.pos = target;
  }
  flush();
  if (!units_seen) {
    dr.units = "mm (assumed)";
    dr.warnings.push_back(path + ": no G20/G21: coordinates taken as millimetres");
  }
  dr.entity_counts["G-code path"] = static_cast<int>(dr.curves.size());
  return dr;
}

}  // namespace host
