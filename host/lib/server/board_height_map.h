// The height map of a board job (issue 25, the workshop): the area a probe-first job probes,
// the map kept in its archive folder, and the map a bottom-side job takes over from the top
// side's job once the blank has been flipped on its alignment pins.
#ifndef HOST_LIB_SERVER_BOARD_HEIGHT_MAP_H
#define HOST_LIB_SERVER_BOARD_HEIGHT_MAP_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <filesystem>  // std::filesystem::path
#include <functional>  // std::function
#include <optional>    // std::optional
#include <string>      // std::string

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"  // AreaMm
#include "host/lib/plan/job_plan.h"
#include "host/lib/server/board_planning.h"  // BoardSettings
#include "host/lib/server/data_folder.h"
#include "host/lib/server/job_store.h"

namespace host::server {

// The archive's map of a job (its probe or the one it took over) and its picture.
extern const char kHeightMapFile[];         // "heightmap.json"
extern const char kHeightMapMachineFile[];  // "heightmap.machine": the machine probed on
extern const char kHeightMapPicture[];      // "heightmap.svg"

// The probe area in board.json (probe_area_mm: X0, Y0, X1, Y1): pcb::board_probe_area.
nlohmann::json area_json(const heightmap::AreaMm& a);
heightmap::AreaMm area_of_json(const nlohmann::json& j);

// The top side's map for the bottom side's setup. The setups share the machine frame (the
// bottom job is planned mirrored about the flip axis, on the pins the top job drilled), and
// the tool is zeroed on the copper at the machine's zero corner in both. flip:
//  - "table": the height belongs to the machine (a trammed-off table, a spoil board that is
//    not flat, a thin blank held flat on it): the same heights at the same machine places.
//  - "blank": the height belongs to the blank (a stiff, bowed blank clamped at its edges):
//    flipped with it, so a place of the new surface at x lies where x' = 2 a - x was, and
//    what was high is now low: h'(x, y) = -(h(2a - x, y) - h(2a, 0)), re-zeroed at (0, 0).
// Throws HeightMapError for an unknown flip.
heightmap::HeightMap map_after_flip(const heightmap::HeightMap& top, double flip_axis_x_mm,
                                    const std::string& flip);

// The machine a job folder's map was probed on ("" when none is named).
std::string map_probed_on(const std::filesystem::path& job_dir);
// Keeps a job's map, its picture and its machine in its archive folder.
void keep_height_map(const std::filesystem::path& job_dir, const heightmap::HeightMap& map,
                     const std::string& title, const std::string& machine);

// Why a height_map_from job cannot have `from`'s map: "job 4 ended failed without a height
// map (its message)"; "" when `from` has not ended so (it may still probe, or completed).
std::string source_ended_text(const JobRecord& from);

// The map a height_map_from job cuts with: its source job's, flipped as asked, checked
// against `plan` and only then kept in `job_dir`. Throws std::runtime_error with the reason
// (no such job, the source ended or has no map yet, another machine's map, no flip axis, a
// map that does not cover the job).
heightmap::HeightMap map_from_source_job(JobStore& store, const DataFolder& data,
                                         const std::filesystem::path& job_dir,
                                         const std::string& job_name, const BoardSettings& board,
                                         const std::string& machine, const JobPlan& plan,
                                         const std::function<void(const std::string&)>& note);

// Why a planned board's height map fields are refused at upload (400), naming the field;
// "" when fine: a probe_spacing_mm that makes more than 16 points a side over the probe
// area, height_map_flip=blank from a job without alignment holes, and a source job's map
// (when it has one already) that does not cover this job where it will lie.
std::string check_height_map_fields(JobStore& store, const DataFolder& data,
                                    const BoardSettings& board, const PlannedBoard& planned);

// The height map's messages (the library's, worded for the command line) with the
// server's fields: probe_first=1 for --probe, and no --outlier-limit (the server keeps it).
std::string server_map_words(std::string text);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_BOARD_HEIGHT_MAP_H
