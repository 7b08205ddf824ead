// Splits the simulated tool path into the runs made at one depth (see cut_paths.h).
#include "host/lib/sim/cut_paths.h"

#include <cmath>  // std::abs

namespace host::sim {

CutPathCollector::CutPathCollector(double depth_z_mm, double band_mm)
    : z_mm_(depth_z_mm), band_mm_(band_mm) {}

namespace {
const double kMovedMm = 0.001;  // one micrometre: the model's position is exact below that
}  // namespace

void CutPathCollector::drop_unmoved() {
  if (!paths_.empty() && !moved_) {
    samples_ -= paths_.back().size();
    paths_.pop_back();
  }
  moved_ = true;  // nothing pending
}

void CutPathCollector::add(const ToolSample& s) {
  const bool at_depth = std::abs(s.z_mm - z_mm_) <= band_mm_;
  if (!at_depth) {
    inside_ = false;
    return;
  }
  const Point2 p(s.x_mm, s.y_mm);
  if (!inside_) {
    drop_unmoved();
    paths_.emplace_back();
    moved_ = false;
  }
  inside_ = true;
  std::vector<Point2>& path = paths_.back();
  if (!moved_ && !path.empty() && (p - path.front()).norm() > kMovedMm) moved_ = true;
  path.push_back(p);
  ++samples_;
}

const std::vector<std::vector<Point2>>& CutPathCollector::paths() {
  drop_unmoved();
  inside_ = false;  // a later sample at the depth starts a new path
  return paths_;
}

}  // namespace host::sim
