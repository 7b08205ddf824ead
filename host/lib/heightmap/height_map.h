// The height map of a blank: heights (um) probed on a regular grid (mm), as kept in a plain
// JSON file with the job (format in docs/user-guide.md), interpolated as the controller does.
#ifndef HOST_LIB_HEIGHTMAP_HEIGHT_MAP_H
#define HOST_LIB_HEIGHTMAP_HEIGHT_MAP_H

#include <optional>   // std::optional
#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

namespace host::heightmap {

// A map file or map that cannot be used; the message names the file and the field.
class HeightMapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The controller keeps at most this many points per side (issue 25: 16 x 16).
constexpr int kMaxGridSide = 16;
// A blank whose probed heights span more than this is a setup error (not clamped flat, or a
// bad probe), never compensated.
constexpr double kMaxMapRangeUm = 1000.0;
// The controller's grid pitch: 1 mm to 65.535 mm (a u16 in um, #A).
constexpr double kMinPitchMm = 1.0;
constexpr double kMaxPitchMm = 65.535;

struct HeightMap {
  double origin_x_mm = 0, origin_y_mm = 0;  // the grid's point (row 0, col 0)
  double pitch_x_mm = 0, pitch_y_mm = 0;    // between columns (X) and rows (Y)
  int rows = 0, cols = 0;                   // rows along Y, columns along X
  std::vector<double> heights_um;           // row-major: [row * cols + col], above Z 0
  std::optional<double> repeatability_um;   // largest difference of a point probed twice
  std::string probed_at;                    // UTC, ISO 8601
  std::string blank;                        // the blank's name (operator's words), may be ""

  double height_um(int row, int col) const { return heights_um[row * cols + col]; }
  double x_mm(int col) const { return origin_x_mm + col * pitch_x_mm; }
  double y_mm(int row) const { return origin_y_mm + row * pitch_y_mm; }
  double max_x_mm() const { return x_mm(cols - 1); }
  double max_y_mm() const { return y_mm(rows - 1); }
  // Inside the grid's rectangle (its edge included, within 1 nm).
  bool covers(double x_mm, double y_mm) const;
  // Bilinear between the four points around (x, y); outside, the nearest edge value.
  double interpolate_um(double x_mm, double y_mm) const;
  double min_um() const;
  double max_um() const;
};

// Throws HeightMapError naming `what` (a file name) when the map breaks a rule: 2 to 16
// points a side, pitches 1 to 65.535 mm, finite numbers, one height per point, heights
// spanning at most 1 mm with Z 0.
void validate(const HeightMap& map, const std::string& what);

// The file's text (JSON) and back; read_height_map_text validates and names `what`.
std::string height_map_text(const HeightMap& map);
HeightMap read_height_map_text(const std::string& text, const std::string& what);
// Files: errors name the path; the writer writes a validated map only.
HeightMap read_height_map_file(const std::string& path);
void write_height_map_file(const HeightMap& map, const std::string& path);

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_HEIGHT_MAP_H
