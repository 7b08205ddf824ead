// Text from input files on a terminal: a reader's message or a curve's name may quote bytes
// of a binary or foreign-encoded file.
#ifndef HOST_CLI_TERMINAL_TEXT_H
#define HOST_CLI_TERMINAL_TEXT_H

#include <string>  // std::string

namespace host::cli {

// Control characters (escape sequences among them) and bytes that are not UTF-8 as \xNN;
// newlines, tabs and UTF-8 text ("µm") as they are.
std::string printable(const std::string& text);

}  // namespace host::cli

#endif  // HOST_CLI_TERMINAL_TEXT_H
