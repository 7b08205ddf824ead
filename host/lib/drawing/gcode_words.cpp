// G-code line splitting; see gcode_words.h.
#include "host/lib/drawing/gcode_words.h"

#include <cctype>   // std::isalpha, std::toupper
#include <cmath>    // std::isfinite, std::fabs
#include <cstdlib>  // std::strtod

#include "host/lib/drawing/drawing.h"

namespace host {

namespace {

// "(MSG, text)" (LinuxCNC: MSG in any case, then a comma): the text, trimmed.
bool message_of(const std::string& comment, std::string* text) {
  size_t i = 0;
  while (i < comment.size() && comment[i] == ' ') ++i;
  if (comment.size() < i + 4) return false;
  for (size_t k = 0; k < 3; ++k) {
    if (std::toupper(static_cast<unsigned char>(comment[i + k])) != "MSG"[k]) return false;
  }
  if (comment[i + 3] != ',') return false;
  std::string t = comment.substr(i + 4);
  const size_t a = t.find_first_not_of(' ');
  const size_t b = t.find_last_not_of(' ');
  *text = a == std::string::npos ? "" : t.substr(a, b - a + 1);
  return true;
}

}  // namespace

GcodeBlock parse_gcode_line(const std::string& raw, const std::string& where) {
  GcodeBlock block;
  size_t i = 0;
  while (i < raw.size()) {
    const char c = raw[i];
    if (c == ';') break;
    if (c == '(') {
      const size_t close = raw.find(')', i);
      if (close == std::string::npos) throw ImportError(where + ": comment '(' is not closed");
      std::string text;
      if (message_of(raw.substr(i + 1, close - i - 1), &text)) block.message = text;
      i = close + 1;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c)) || c == '%') {
      ++i;
      continue;
    }
    if (c == '#' || c == '[') {
      throw ImportError(where +
                        ": parameters and expressions ('#', '[ ]') are not supported; "
                        "export plain numbers from the CAM program");
    }
    if (c == '/') throw ImportError(where + ": block delete '/' is not supported");
    if (!std::isalpha(static_cast<unsigned char>(c))) {
      throw ImportError(where + ": unexpected '" + std::string(1, c) + "'");
    }
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (letter == 'O') {
      throw ImportError(where + ": O-words (subroutines, loops) are not supported");
    }
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
    block.words.push_back(GcodeWord{letter, v});
  }
  return block;
}

}  // namespace host
