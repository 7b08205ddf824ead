// The height map of a board job (issue 25, the workshop): the area a probe-first job probes,
// the map kept in its archive folder, and the map a bottom-side job takes over from the top
// side's job once the blank has been flipped on its alignment pins.
#ifndef HOST_LIB_SERVER_BOARD_HEIGHT_MAP_H
#define HOST_LIB_SERVER_BOARD_HEIGHT_MAP_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <filesystem>  // std::filesystem::path
#include <optional>    // std::optional
#include <string>      // std::string

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"  // AreaMm
#include "host/lib/pcb/board_job.h"

namespace host::server {

// The archive's map of a job (its probe or the one it took over) and its picture.
extern const char kHeightMapFile[];         // "heightmap.json"
extern const char kHeightMapMachineFile[];  // "heightmap.machine": the machine probed on
extern const char kHeightMapPicture[];      // "heightmap.svg"

// Where a probe-first job probes (machine frame): everywhere it cuts, and for a board with
// alignment holes also where its bottom side will cut after the flip (the mirror about the
// flip axis, the outline's cut-out included), so the bottom job can use the same map.
// nullopt for a job that cuts nothing.
std::optional<heightmap::AreaMm> board_probe_area(const pcb::BoardJob& job);
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

}  // namespace host::server

#endif  // HOST_LIB_SERVER_BOARD_HEIGHT_MAP_H
