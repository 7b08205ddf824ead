// `engraver info` and `engraver points` as functions: what a drawing or a PCB file holds
// (as JSON and as the text `info` prints), and the points the firmware core generates for
// a drawing's curves. PCB input of `points` is board_points() (board_input.h).
#ifndef HOST_LIB_COMMANDS_INFO_COMMAND_H
#define HOST_LIB_COMMANDS_INFO_COMMAND_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <optional>  // std::optional
#include <string>    // std::string
#include <vector>    // std::vector

#include "host/lib/drawing/drawing.h"
#include "host/lib/pcb/pcb_layer.h"  // PcbLayer

namespace host::commands {

// A Gerber or Excellon file as its reader reads it.
struct PcbFileInfo {
  pcb::PcbLayer layer;
  std::string format;  // "Gerber RS-274X" or "Excellon"
};
// Reads `path` when it is a Gerber or Excellon file (by name or content); nullopt for any
// other file. A file that cannot be read ends the command (CommandFailure, exit 2).
std::optional<PcbFileInfo> read_pcb_file_info(const std::string& path);
// Its layer, units, extents, apertures or tools, polygons, holes and notes.
nlohmann::json pcb_info_json(const PcbFileInfo& info);
std::string pcb_info_text(const PcbFileInfo& info);

// A board folder as `board` reads it: which file is taken for which layer and why, which are
// left out, and each layer read (copper of both sides, drill, outline).
struct BoardFolderInfo {
  std::string folder;
  std::string board;               // the board's name (the folder's)
  std::vector<std::string> files;  // "FILE: taken as top copper (from its name)", "...: left out"
  std::vector<PcbFileInfo> layers;
};
// Reads `path` when it is a folder; nullopt for anything else. A folder without Gerber or
// Excellon files, or a file there that cannot be read, ends the command (exit 2).
std::optional<BoardFolderInfo> read_board_folder_info(const std::string& path);
// The folder's files, then each layer's summary as for a single file.
nlohmann::json board_folder_info_json(const BoardFolderInfo& info);
std::string board_folder_info_text(const BoardFolderInfo& info);

// A drawing's entities, units, extents, curves (every knot and control point in JSON, the
// first few in text), program operations and problems.
nlohmann::json drawing_info_json(const Drawing& d);
std::string drawing_info_text(const Drawing& d);

// `points --tol` in whole micrometres (the firmware's chord tolerance); outside 0.001 .. 10
// mm ends the command (exit 2).
int points_tolerance_um(double tol_mm);
// The points the firmware core generates for curve `curve`; a curve it cannot hold ends the
// command (exit 1) naming the file and the curve.
std::vector<Point2> curve_points(const Drawing& d, size_t curve, int tol_um);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_INFO_COMMAND_H
