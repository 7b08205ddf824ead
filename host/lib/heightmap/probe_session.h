// Probing a blank into a height map, whatever does the touching (the controller's probe
// command through the sender, or a model in tests): the grid in serpentine order, each
// point once or twice, points that disagree with their neighbours probed again, and refused
// with their places if they still do.
#ifndef HOST_LIB_HEIGHTMAP_PROBE_SESSION_H
#define HOST_LIB_HEIGHTMAP_PROBE_SESSION_H

#include <functional>  // std::function
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/probe_grid.h"

namespace host::heightmap {

struct ProbeOptions {
  GridOptions grid;
  bool twice = false;            // each point probed twice: the map records repeatability
  double outlier_limit_um = 25;  // from the neighbours' prediction (and between two touches)
  std::string blank;             // kept in the map
};

// One touch at (x, y) mm: the contact height in um above Z 0. Throws what the probe's
// failure is (no contact, spindle on, ...); the session passes it on.
using ProbeTouch = std::function<double(double x_mm, double y_mm)>;
// Touches made so far and how many the grid needs (re-probes add to both).
using ProbeProgress = std::function<void(size_t done, size_t planned)>;

// Points still disagreeing with their neighbours after being probed again.
class ProbeRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ProbeRun {
  HeightMap map;
  size_t touches = 0;
  std::vector<std::string> reprobed;  // the points probed again, described, and what they read
};

// Probes the grid over `job` and returns the map (validated). Throws ProbeRefused,
// GridError, HeightMapError (range), or what `touch` throws.
ProbeRun probe_blank(const AreaMm& job, const ProbeOptions& options, const ProbeTouch& touch,
                     const ProbeProgress& progress = nullptr);

// The current time as the map keeps it: "2026-11-27T19:50:00Z".
std::string utc_now_iso8601();

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_PROBE_SESSION_H
