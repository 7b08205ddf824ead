// The depth of cut along a board's isolation paths, measured from the executed tool path
// against the blank's TRUE surface (not the map the controller followed): depth error, the
// V-bit's groove width against plan, and where the copper was not cut through.
#ifndef HOST_LIB_HEIGHTMAP_DEPTH_METER_H
#define HOST_LIB_HEIGHTMAP_DEPTH_METER_H

#include <cstddef>  // size_t
#include <vector>   // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"

namespace host::heightmap {

struct DepthOptions {
  double isolation_z_mm = -0.05;  // the planned cutting height on a flat blank (machine Z)
  double vbit_angle_deg = 30.0;   // included angle of the V-bit
  double planned_width_um = 200;  // the groove's width at the planned depth (--tool-width)
  double copper_um = 35;          // copper thickness (1 oz): shallower does not isolate
  double band_um = 20;            // a sample within this of the planned height is isolation
  double keep_step_mm = 0.05;     // the plot's samples: one every this many mm of path
};

// One kept sample for the plot: where, and how much too deep (+) or too shallow (-).
struct DepthSample {
  double x_mm = 0, y_mm = 0, error_um = 0;
  bool starts_path = false;
};

struct DepthReport {
  size_t samples = 0;       // isolation samples measured
  double length_mm = 0;     // of isolation path measured
  double max_error_um = 0;  // largest |depth - planned depth|, with its sign
  double max_error_at_mm[2] = {0, 0};
  double rms_error_um = 0;  // along the path (length-weighted)
  double min_depth_um = 0, max_depth_um = 0;
  double planned_depth_um = 0;
  double planned_width_um = 0;
  double min_width_um = 0, max_width_um = 0;  // of the groove at the copper's top
  double max_width_error_um = 0;              // largest |width - planned|, with its sign
  double uncut_mm = 0;  // isolation path whose depth is less than the copper's thickness
  double uncut_share = 0;
  std::vector<DepthSample> kept;  // for the plot (DepthOptions::keep_step_mm apart)
};

class DepthMeter {
 public:
  // `applied` is the map the controller compensated with (nullptr: none), so a sample's
  // planned height is its Z less the map's height there; its depth is the TRUE surface's
  // height there less its Z.
  DepthMeter(const SurfaceModel& truth, const HeightMap* applied, const DepthOptions& options);
  // The map the controller follows from now on (probed after the meter was made).
  void set_applied_map(const HeightMap* applied) { applied_ = applied; }
  // One executed tool position (machine frame, mm), in time order.
  void add(double x_mm, double y_mm, double z_mm);
  DepthReport report() const;

 private:
  const SurfaceModel& truth_;
  const HeightMap* applied_;
  DepthOptions o_;
  double half_tan_ = 0;  // tan(angle / 2): width grows 2 * half_tan_ per um deeper
  bool inside_ = false;
  bool starts_path_ = false;  // the next moving sample begins a path in the plot
  double last_x_ = 0, last_y_ = 0, last_error_ = 0, kept_from_mm_ = 0;
  double sum_sq_ = 0;  // error squared times length
  bool any_ = false;
  DepthReport r_;
};

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_DEPTH_METER_H
