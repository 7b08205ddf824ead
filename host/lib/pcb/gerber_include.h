// %IF (include file, deprecated): the named file's blocks in place of the %IF block, as gerbv
// reads them. Only a file on disk can include: an upload has no folder to look in.
#ifndef HOST_LIB_PCB_GERBER_INCLUDE_H
#define HOST_LIB_PCB_GERBER_INCLUDE_H

#include <string>  // std::string

namespace host::pcb {

// `text` (the file at `path`) with every %IF<name>*% block replaced by the text of <name>, a
// path relative to `path`'s folder (neither absolute nor through ".."), its own includes
// expanded (at most 8 deep). The included text's line ends are left out, so the including
// file's line numbers stay true (a problem inside the included blocks is reported at the %IF
// line). Throws PcbReadError naming the file and the %IF line when the name is not allowed,
// the file cannot be read or the includes go too deep.
std::string expand_gerber_includes(const std::string& text, const std::string& path);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_GERBER_INCLUDE_H
