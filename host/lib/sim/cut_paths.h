// The simulated tool-centre paths at one cutting depth, as polylines (mm), so that checks
// made on the planned paths (e.g. the isolation check of a board) can be made on what the
// simulated machine really did.
#ifndef HOST_LIB_SIM_CUT_PATHS_H
#define HOST_LIB_SIM_CUT_PATHS_H

#include <cstddef>  // size_t
#include <vector>   // std::vector

#include "host/lib/drawing/bspline.h"  // Point2
#include "host/lib/sim/sim_machine.h"  // ToolSample

namespace host::sim {

class CutPathCollector {
 public:
  // Samples with |z - depth_z_mm| <= band_mm are at the depth; a run of them that moves in
  // X/Y is one path (a plunge passing through the depth, e.g. a drill's, is not a cut).
  CutPathCollector(double depth_z_mm, double band_mm);
  void add(const ToolSample& s);
  // The paths so far (the newest one only once it has moved).
  const std::vector<std::vector<Point2>>& paths();
  size_t samples() const { return samples_; }

 private:
  double z_mm_, band_mm_;
  void drop_unmoved();

  bool inside_ = false;
  bool moved_ = false;  // the newest path left its first point
  size_t samples_ = 0;
  std::vector<std::vector<Point2>> paths_;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_CUT_PATHS_H
