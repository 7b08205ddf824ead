// Pictures of a blank's height map (heights as colours, the probe points on it) and of the
// depth error along a board's isolation paths (the path coloured by how far too deep or too
// shallow it was cut), as SVG files (cairo).
#ifndef HOST_LIB_PLOT_HEIGHT_MAP_PLOT_H
#define HOST_LIB_PLOT_HEIGHT_MAP_PLOT_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/heightmap/depth_meter.h"
#include "host/lib/heightmap/height_map.h"

namespace host {

// The map's heights (bilinear, as the controller uses them) with its probe points marked.
// Throws std::runtime_error naming the file when it cannot be written.
void write_height_map_svg(const heightmap::HeightMap& map, const std::string& title,
                          const std::string& svg_path);

// The isolation paths coloured by depth error: red too deep, blue too shallow, green within
// +-range_um/4; the colour scale runs -range_um .. +range_um.
void write_depth_error_svg(const std::vector<heightmap::DepthSample>& samples, double range_um,
                           const std::string& title, const std::string& svg_path);

}  // namespace host

#endif  // HOST_LIB_PLOT_HEIGHT_MAP_PLOT_H
