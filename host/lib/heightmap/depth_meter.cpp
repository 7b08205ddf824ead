// Depth of cut along the isolation paths against the true surface (depth_meter.h).
#include "host/lib/heightmap/depth_meter.h"

#include <algorithm>  // std::min
#include <cmath>      // std::tan

namespace host::heightmap {

namespace {
constexpr double kPi = 3.14159265358979323846;
const double kMovedMm = 0.001;  // the model's position is exact below a micrometre
}  // namespace

DepthMeter::DepthMeter(const SurfaceModel& truth, const HeightMap* applied,
                       const DepthOptions& options)
    : truth_(truth), applied_(applied), o_(options) {
  half_tan_ = std::tan(o_.vbit_angle_deg * kPi / 360.0);
  r_.planned_depth_um = -o_.isolation_z_mm * 1000.0;
  r_.planned_width_um = o_.planned_width_um;
}

void DepthMeter::add(double x, double y, double z_mm) {
  const double z_um = z_mm * 1000.0;
  const double planned_z_um = z_um - (applied_ ? applied_->interpolate_um(x, y) : 0.0);
  if (std::abs(planned_z_um - o_.isolation_z_mm * 1000.0) > o_.band_um) {
    inside_ = false;
    return;
  }
  const double depth = truth_.height_um(x, y) - z_um;
  const double error = depth - r_.planned_depth_um;
  const double step = inside_ ? std::hypot(x - last_x_, y - last_y_) : 0.0;
  const bool starts = !inside_;
  inside_ = true;
  // Only the tool moving along the path cuts the groove: the last micrometres of a plunge
  // or the first of a lift, at one place, are not the path's depth.
  if (step <= kMovedMm) {
    if (starts) {
      last_x_ = x;
      last_y_ = y;
      starts_path_ = true;
    }
    last_error_ = error;  // the plunge's depth when the tool sets off
    return;
  }
  const double width = o_.planned_width_um + 2.0 * half_tan_ * error;
  if (!any_) {
    r_.min_depth_um = r_.max_depth_um = depth;
    r_.min_width_um = r_.max_width_um = width;
    any_ = true;
  }
  ++r_.samples;
  r_.min_depth_um = std::min(r_.min_depth_um, depth);
  r_.max_depth_um = std::max(r_.max_depth_um, depth);
  r_.min_width_um = std::min(r_.min_width_um, width);
  r_.max_width_um = std::max(r_.max_width_um, width);
  if (std::abs(width - o_.planned_width_um) > std::abs(r_.max_width_error_um))
    r_.max_width_error_um = width - o_.planned_width_um;
  if (std::abs(error) > std::abs(r_.max_error_um)) {
    r_.max_error_um = error;
    r_.max_error_at_mm[0] = x;
    r_.max_error_at_mm[1] = y;
  }
  // Along the path: the segment's error is its ends' mean (the path's first end is the
  // place the plunge reached, at the depth it reached there).
  const double mean = 0.5 * (error + last_error_);
  r_.length_mm += step;
  sum_sq_ += mean * mean * step;
  if (mean + r_.planned_depth_um < o_.copper_um) r_.uncut_mm += step;
  if (starts_path_ || r_.length_mm - kept_from_mm_ >= o_.keep_step_mm) {
    if (starts_path_) r_.kept.push_back(DepthSample{last_x_, last_y_, error, true});
    r_.kept.push_back(DepthSample{x, y, error, false});
    kept_from_mm_ = r_.length_mm;
    starts_path_ = false;
  }
  last_x_ = x;
  last_y_ = y;
  last_error_ = error;
}

DepthReport DepthMeter::report() const {
  DepthReport r = r_;
  r.rms_error_um = r.length_mm > 0 ? std::sqrt(sum_sq_ / r.length_mm) : 0.0;
  r.uncut_share = r.length_mm > 0 ? r.uncut_mm / r.length_mm : 0.0;
  return r;
}

}  // namespace host::heightmap
