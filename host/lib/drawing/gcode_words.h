// The words of one G-code line (RS-274 / LinuxCNC): letters with numbers, comments removed,
// the text of a "(MSG, ...)" comment kept for the operator.
#ifndef HOST_LIB_DRAWING_GCODE_WORDS_H
#define HOST_LIB_DRAWING_GCODE_WORDS_H

#include <string>  // std::string
#include <vector>  // std::vector

namespace host {

struct GcodeWord {
  char letter;  // upper case
  double value;
};

struct GcodeBlock {
  std::vector<GcodeWord> words;  // in line order; N line numbers included
  std::string message;           // text of "(MSG, text)", "" when none
};

// Splits one line. `where` ("file: line 12") starts every error message. Throws ImportError
// for a malformed word, an unclosed comment, parameters/expressions and O-words.
GcodeBlock parse_gcode_line(const std::string& line, const std::string& where);

}  // namespace host

#endif  // HOST_LIB_DRAWING_GCODE_WORDS_H
