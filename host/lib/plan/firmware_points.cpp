// Runs the firmware's curve walker on the host (see firmware_points.h).
#include "host/lib/plan/firmware_points.h"

#include <sstream>  // std::ostringstream

#include "firmware/core/curve_walker.h"
#include "host/lib/plan/firmware_spline.h"

namespace host {

std::vector<core::PointUm> firmware_points_um(const std::vector<core::Spline>& pieces,
                                              int chord_tolerance_um, int32_t tool_offset_um) {
  if (chord_tolerance_um < 1 || chord_tolerance_um > 10000) {
    throw ConversionError("chord tolerance must be 1..10000 um");
  }
  std::vector<core::PointUm> out;
  for (size_t k = 0; k < pieces.size(); ++k) {
    core::StepSettings st = core::default_step_settings();
    st.mode = core::StepMode::kAdaptive;
    st.chord_tolerance_um = static_cast<uint16_t>(chord_tolerance_um);
    st.tool_offset_um = tool_offset_um;
    core::CurveWalker walker;
    core::GeometryError e = walker.begin(&pieces[k], st);
    core::PointUm p;
    bool first = true;
    // Bounded: a spline of at most 64 control points over a +-1 m range at >= 1 um
    // tolerance cannot need more points than this.
    const size_t limit = 10000000;
    size_t count = 0;
    while (e == core::GeometryError::kOk && walker.next(&p)) {
      if (!(first && k > 0)) out.push_back(p);
      first = false;
      if (++count > limit) throw ConversionError("the curve walker did not finish the curve");
    }
    if (e == core::GeometryError::kOk) e = walker.error();
    if (e != core::GeometryError::kOk) {
      std::ostringstream o;
      o << "the firmware's point generator stopped on piece " << k << " with geometry error "
        << static_cast<int>(e);
      throw ConversionError(o.str());
    }
  }
  return out;
}

std::vector<Point2> firmware_points_mm(const BSpline& curve_mm, int chord_tolerance_um) {
  std::vector<Point2> out;
  for (const core::PointUm& p :
       firmware_points_um(to_firmware_splines(curve_mm), chord_tolerance_um)) {
    out.emplace_back(p.x_um / 1000.0, p.y_um / 1000.0);
  }
  return out;
}

}  // namespace host
