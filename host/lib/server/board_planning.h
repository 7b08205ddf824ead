// Boards as server jobs: the uploaded Gerber/Excellon files of one board are read from
// memory (their names only name them in messages), planned with the board planner, and
// kept in the archive under the server's own names with a manifest (board.json) that
// lets the machine's worker (or another server sharing the queue) plan them again.
#ifndef HOST_LIB_SERVER_BOARD_PLANNING_H
#define HOST_LIB_SERVER_BOARD_PLANNING_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <cstdint>     // int64_t
#include <filesystem>  // std::filesystem::path
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/pcb/board_job.h"
#include "host/lib/server/board_bundle.h"
#include "host/lib/server/job_record.h"

namespace host::server {

// The archive's manifest of a board job; JobRecord::input_file of every board job.
extern const char kBoardManifest[];  // "board.json"
bool is_board_job(const JobRecord& job);

struct UploadFile {
  std::string name;     // the sender's file name (messages only, never a path)
  std::string content;  // its bytes
};

// What a board job asks beyond JobPlanSettings (tol_mm and margin_mm apply to boards;
// feeds are the board planner's defaults, host/lib/plan/job_defaults.h). Every board job
// starts with a pause naming the first tool (the operator mounts it and confirms).
struct BoardSettings {
  std::string side;  // "top", "bottom" or "" (the side whose copper is given)
  double tool_width_mm = defaults::kToolWidthMm;
  bool allow_narrow_gaps = false;  // plan where copper is closer than the tool (reported)
  // The command line's --passes, --clearing-tool and --narrow-passes.
  int passes = defaults::kPasses;
  double clearing_tool_mm = 0;  // > 0: a wider tool for the outer passes
  int narrow_passes = 1;
  // Double-sided (--align-holes, --align-diameter, --align-depth, --align-measured):
  // "auto" or "X,Y[;X,Y...]" (files' frame, mm); "" none. Measured: X1 Y1 X2 Y2 or empty.
  std::string align_holes;
  double align_diameter_mm = defaults::kAlignDiameterMm;
  double align_depth_mm = defaults::kAlignDepthMm;
  std::vector<double> align_measured_mm;
  // The height map (board_height_map.h): probe the blank first, or use the map another job
  // (the top side of this board, flipped on its pins since) probed. 0: none.
  bool probe_first = false;
  double probe_spacing_mm = 10.0;  // the probe grid's largest pitch (probe --probe-spacing)
  int64_t height_map_from = 0;
  std::string height_map_flip = "table";  // how the reused map follows the flip
};
// Why board settings are refused ("" when fine): the command line's ranges (job_defaults.h).
std::string check_board_settings(const BoardSettings& s);
// "auto" or "X,Y[;X,Y...]" into the planner's options; "" when fine, else why not.
std::string parse_align_holes(const std::string& text, std::vector<Point2>* holes_file_mm);

// Gerber or Excellon by name and content.
bool is_pcb_upload(const UploadFile& file);

struct PlannedBoard {
  NamedFiles files;  // the archive's files: board.json, then the layers (server names)
  pcb::BoardJob job;
  nlohmann::json manifest;
};

// Reads and plans one board. skip_other: leave out files that are neither Gerber nor
// Excellon (a folder's read-me) instead of refusing them. Throws ImportError (a file that
// cannot be read: the reader's message with the file's name and line) or PlanError (the
// planner's message: narrow gaps, the work area, an outline that does not close).
PlannedBoard plan_board_upload(const std::vector<UploadFile>& files, bool skip_other,
                               const std::string& board_name, const BoardSettings& board,
                               const JobPlanSettings& settings, double work_w_mm, double work_h_mm);

// The board settings a manifest (board.json) was planned with; read_board_settings reads
// the archive folder's (throws std::runtime_error naming a damaged one).
BoardSettings board_settings_of(const nlohmann::json& manifest);
BoardSettings read_board_settings(const std::filesystem::path& dir);

// Plans a board job again from its archive folder (board.json and the layer files).
pcb::BoardJob plan_board_folder(const std::filesystem::path& dir, const JobPlanSettings& settings,
                                double work_w_mm, double work_h_mm);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_BOARD_PLANNING_H
