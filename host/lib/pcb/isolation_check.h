// Geometric checks of an isolation job, independent of how it was planned: the swept tool
// (the tool-centre paths grown by the tool radius) never overlaps copper beyond a stated
// tolerance, and every pair of separate copper islands ends up in separate pieces of the
// material the tool leaves standing.
#ifndef HOST_LIB_PCB_ISOLATION_CHECK_H
#define HOST_LIB_PCB_ISOLATION_CHECK_H

#include <clipper.hpp>  // ClipperLib::Paths

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/drawing/bspline.h"   // Point2
#include "host/lib/pcb/pcb_geometry.h"  // Island

namespace host::pcb {

// Copper the tool removes beyond the tolerance.
struct CopperHit {
  Point2 at_mm{0, 0};   // middle of the overlap
  double area_mm2 = 0;  // of copper inside the tool grown by less the tolerance
};

// Two islands of copper that no cut separates.
struct UnseparatedPair {
  size_t island_a = 0, island_b = 0;  // indices in copper_islands() order
  Point2 a_mm{0, 0}, b_mm{0, 0};      // a point inside each
};

struct IsolationCheck {
  size_t islands = 0;
  std::vector<CopperHit> hits;
  std::vector<UnseparatedPair> unseparated;
  bool ok() const { return hits.empty() && unseparated.empty(); }
};

// copper_nm and the paths in one frame (the machine frame for a planned job). Paths are
// tool-centre polylines (mm) traced with the tool down; each is swept by a disc. Samples
// within a tenth of the tolerance of a straight run are left out before the sweep.
IsolationCheck check_isolation(const ClipperLib::Paths& copper_nm,
                               const std::vector<std::vector<Point2>>& tool_paths_mm,
                               double tool_radius_mm, double tolerance_mm);
// The same for copper already split into islands (copper_islands): islands are numbered as
// given.
IsolationCheck check_isolation(const std::vector<Island>& islands,
                               const std::vector<std::vector<Point2>>& tool_paths_mm,
                               double tool_radius_mm, double tolerance_mm);

// One line per finding, for the CLI and test messages.
std::string describe(const IsolationCheck& c);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_ISOLATION_CHECK_H
