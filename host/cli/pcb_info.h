// `engraver info` for PCB files (Gerber, Excellon): what the readers make of them.
#ifndef HOST_CLI_PCB_INFO_H
#define HOST_CLI_PCB_INFO_H

#include <string>  // std::string

namespace host::cli {

// If `path` is a Gerber or Excellon file (by name or content), reads it and prints the layer
// summary (text or JSON) and returns true; false for any other file. A file that cannot be
// read ends the command with CommandFailure (usage/input exit code).
bool print_pcb_info_if_pcb(const std::string& path, bool json);
// If `path` is a folder, reads it as `board` does and prints which file was taken for which
// layer (and which were left out, and why), then each layer's summary; false for a file.
bool print_board_folder_info_if_folder(const std::string& path, bool json);

}  // namespace host::cli

#endif  // HOST_CLI_PCB_INFO_H
