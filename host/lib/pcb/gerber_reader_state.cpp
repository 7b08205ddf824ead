#include "host/lib/pcb/gerber_reader_state.h"

#include <cmath>    // std::isfinite
#include <cstdlib>  // std::strtod

#include "host/lib/pcb/pcb_layer.h"  // PcbReadError

namespace host::pcb::gerber {

void GerberDiagnostics::fail(const std::string& what) const {
  throw PcbReadError(path + ":" + std::to_string(line) + ": " + what);
}

void GerberDiagnostics::note(const std::string& text) {
  for (Note& n : notes_) {
    if (n.text == text) {
      ++n.count;
      return;
    }
  }
  notes_.push_back({text, line, 1});
}

void GerberDiagnostics::note_at(const std::string& text, int at_line) {
  notes_.push_back({text, at_line, 1});
}

double GerberDiagnostics::number(const std::string& s, const char* what) const {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v)) {
    fail(std::string("bad ") + what + " '" + s + "'");
  }
  return v;
}

std::vector<std::string> GerberDiagnostics::lines() const {
  std::vector<std::string> out;
  for (const Note& nt : notes_) {
    std::string s = "line " + std::to_string(nt.first_line) + ": " + nt.text;
    if (nt.count > 1) s += " (" + std::to_string(nt.count) + " times)";
    out.push_back(s);
  }
  return out;
}

void GerberUnits::set(GerberDiagnostics& diag, double unit_nm, const char* how) {
  if (nm != 0 && nm != unit_nm) {
    diag.note(std::string("units changed by ") + how + " after coordinates were read");
  }
  nm = unit_nm;
  name = unit_nm == 1e6 ? "mm" : "inch";
}

// No %MO (nor G70/G71) before the first size: the format's legacy default, inch, as gerbv
// and pcb2gcode read it.
void GerberUnits::need(GerberDiagnostics& diag, const std::string& what) {
  if (nm != 0) return;
  set(diag, 25.4e6, "the default");
  diag.note("warning: no units (%MO) before " + what + ": inch assumed (the format's old default)");
}

}  // namespace host::pcb::gerber
