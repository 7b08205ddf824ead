// `engraver info` for PCB files: host/lib/commands/info_command.h's report, printed.
#include "host/cli/pcb_info.h"

#include <iostream>  // std::cout

#include "host/cli/terminal_text.h"  // printable
#include "host/lib/commands/info_command.h"

namespace host::cli {

bool print_board_folder_info_if_folder(const std::string& path, bool json) {
  const std::optional<commands::BoardFolderInfo> info = commands::read_board_folder_info(path);
  if (!info) return false;
  if (json) {
    std::cout << commands::board_folder_info_json(*info).dump(
                     2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
  } else {
    std::cout << printable(commands::board_folder_info_text(*info));
  }
  return true;
}

bool print_pcb_info_if_pcb(const std::string& path, bool json) {
  const std::optional<commands::PcbFileInfo> info = commands::read_pcb_file_info(path);
  if (!info) return false;
  if (json) {
    std::cout << commands::pcb_info_json(*info).dump(2, ' ', false,
                                                     nlohmann::json::error_handler_t::replace)
              << "\n";
  } else {
    std::cout << commands::pcb_info_text(*info);
  }
  return true;
}

}  // namespace host::cli
