// The points the firmware's point generator produces for a curve: the portable core
// (core::CurveWalker) run on the host over the curve's firmware splines.
#ifndef HOST_LIB_PLAN_FIRMWARE_POINTS_H
#define HOST_LIB_PLAN_FIRMWARE_POINTS_H

#include <stdint.h>  // int32_t

#include <vector>  // std::vector

#include "firmware/core/spline.h"
#include "host/lib/drawing/bspline.h"

namespace host {

// Adaptive stepping with the given chord tolerance (micrometres, 1..10000) and tool offset
// (> 0 left of travel). Throws ConversionError when the curve cannot be converted or the
// walker stops early (the message carries the core::GeometryError code).
std::vector<core::PointUm> firmware_points_um(const std::vector<core::Spline>& pieces,
                                              int chord_tolerance_um, int32_t tool_offset_um = 0);

// Same for a host curve (converted with to_firmware_splines), in mm; pieces after the first
// drop their first point (it repeats the previous piece's last).
std::vector<Point2> firmware_points_mm(const BSpline& curve_mm, int chord_tolerance_um);

}  // namespace host

#endif  // HOST_LIB_PLAN_FIRMWARE_POINTS_H
