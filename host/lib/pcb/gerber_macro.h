// Gerber aperture macros (%AM): the statements as read, and their evaluation with the
// parameters of an %AD into polygons (primitives 1, 2/20, 21, 22, 4, 5, 6, 7; variables and
// arithmetic with + - x / and parentheses).
#ifndef HOST_LIB_PCB_GERBER_MACRO_H
#define HOST_LIB_PCB_GERBER_MACRO_H

#include <clipper.hpp>  // ClipperLib::Paths

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

namespace host::pcb {

struct MacroStatement {
  int line = 0;      // where it is in the file
  std::string text;  // whitespace removed, no '*'
};

struct ApertureMacro {
  std::string name;
  int line = 0;
  std::vector<MacroStatement> statements;  // comments (primitive 0) dropped
};

// A macro that cannot be evaluated; `line` is the statement's line in the file.
class MacroError : public std::runtime_error {
 public:
  MacroError(int at_line, const std::string& msg) : std::runtime_error(msg), line(at_line) {}
  int line;
};

// Value of an arithmetic expression of the macro language ($n are vars[n], 'x' or 'X'
// multiplies). Throws std::invalid_argument with the reason.
double evaluate_macro_expression(const std::string& text, const std::vector<double>& vars);

// The aperture's shape in nanometres around its origin: positive outers, negative holes,
// no overlaps. unit_nm: nanometres per file unit.
ClipperLib::Paths evaluate_macro(const ApertureMacro& macro, const std::vector<double>& params,
                                 double unit_nm, double tol_nm);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_GERBER_MACRO_H
