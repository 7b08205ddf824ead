// Where to probe a blank: a grid over the job's extents plus a margin (spacing or rows x
// cols), visited in a serpentine (fewest and shortest travels), and the points that disagree
// with their neighbours (a chip, a dent, a loose clip).
#ifndef HOST_LIB_HEIGHTMAP_PROBE_GRID_H
#define HOST_LIB_HEIGHTMAP_PROBE_GRID_H

#include <optional>  // std::optional
#include <string>    // std::string
#include <vector>    // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"  // AreaMm

namespace host::heightmap {

struct GridOptions {
  double spacing_mm = 10.0;  // the largest pitch; used when rows/cols are 0
  int rows = 0, cols = 0;    // both given: exactly this grid
  double margin_mm = 1.0;    // the grid reaches this far beyond the job on every side, but
                             // not below X 0 / Y 0 where the job does not
};

// The grid's geometry: a HeightMap without heights.
struct ProbeGrid {
  double origin_x_mm = 0, origin_y_mm = 0;
  double pitch_x_mm = 0, pitch_y_mm = 0;
  int rows = 0, cols = 0;
  double x_mm(int col) const { return origin_x_mm + col * pitch_x_mm; }
  double y_mm(int row) const { return origin_y_mm + row * pitch_y_mm; }
};

struct GridPoint {
  int row = 0, col = 0;
};

// A grid that cannot be planned (too many points, an empty job); the message says what to
// change.
class GridError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The grid over `job` grown by the margin: with a spacing, as few points as keep every pitch
// <= spacing (2 to 16 a side); with rows and cols, exactly those.
ProbeGrid plan_probe_grid(const AreaMm& job, const GridOptions& options);
// Every point once: a serpentine along the direction that makes the shorter path, from the
// point (0, 0) of the grid.
std::vector<GridPoint> probe_order(const ProbeGrid& grid);
// The length of the travels between consecutive points of `order` (mm).
double travel_mm(const ProbeGrid& grid, const std::vector<GridPoint>& order);

// A point whose height is further than the limit from what its neighbours predict.
struct Outlier {
  GridPoint point;
  double height_um = 0, predicted_um = 0;
};
// Each point against the median of its neighbours' predictions along each axis
// (quadratics through three or four points where the row or column has them, exact for a
// tilt and a bow; else midpoints and straight-line extrapolations), the most condemned
// point first and then again without it, so one bad point does not condemn the points
// around it. A 2 x 2 grid has no prediction: nothing found.
std::vector<Outlier> find_outliers(const ProbeGrid& grid, const std::vector<double>& heights_um,
                                   double limit_um);
// "row 3, col 5 at (42.000, 17.500) mm reads 61.2 um, its neighbours 12.0 um".
std::string describe_outlier(const ProbeGrid& grid, const Outlier& o);

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_PROBE_GRID_H
