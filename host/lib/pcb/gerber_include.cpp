// Gerber include files (see gerber_include.h).
#include "host/lib/pcb/gerber_include.h"

#include <algorithm>   // std::count
#include <filesystem>  // std::filesystem::path

#include "host/lib/pcb/pcb_layer.h"  // PcbReadError, read_pcb_file_text

namespace host::pcb {

namespace {

const int kMaxIncludeDepth = 8;

std::string expand(const std::string& text, const std::string& path, int depth) {
  std::string out;
  size_t pos = 0;
  for (;;) {
    const size_t at = text.find("%IF", pos);
    const size_t end = at == std::string::npos ? at : text.find("*%", at);
    if (end == std::string::npos) break;
    const std::string name = text.substr(at + 3, end - at - 3);
    const std::string where =
        path + ":" + std::to_string(1 + std::count(text.begin(), text.begin() + at, '\n')) +
        ": include file %IF" + name + ": ";
    const std::filesystem::path rel(name);
    bool up = false;
    for (const auto& part : rel) up = up || part == "..";
    if (name.empty() || rel.is_absolute() || up)
      throw PcbReadError(where + "only a file in this file's folder (or below) is read");
    if (depth >= kMaxIncludeDepth)
      throw PcbReadError(where + "includes nested more than " + std::to_string(kMaxIncludeDepth) +
                         " deep");
    const std::string inc_path = (std::filesystem::path(path).parent_path() / rel).string();
    std::string inc;
    try {
      inc = expand(read_pcb_file_text(inc_path), inc_path, depth + 1);
    } catch (const PcbReadError& e) {
      if (depth > 0) throw;  // named once: the first file's %IF line, then the failing one's
      throw PcbReadError(where + e.what());
    }
    out.append(text, pos, at - pos);
    for (char c : inc)
      if (c != '\n' && c != '\r') out += c;
    pos = end + 2;
  }
  out.append(text, pos, std::string::npos);
  return out;
}

}  // namespace

std::string expand_gerber_includes(const std::string& text, const std::string& path) {
  return text.find("%IF") == std::string::npos ? text : expand(text, path, 0);
}

}  // namespace host::pcb
