// Splines in the form the #Q contour frames carry (firmware/protocol/contour_spline.h):
// lines and circular arcs joined at corners, sent as end points and arc heights. The plan
// holds such a spline exactly as the controller will rebuild it, so what is simulated and
// checked is what the machine cuts.
#ifndef HOST_LIB_PLAN_CONTOUR_FORM_H
#define HOST_LIB_PLAN_CONTOUR_FORM_H

#include <optional>  // std::optional
#include <vector>    // std::vector

#include "firmware/core/spline.h"              // core::Spline
#include "firmware/protocol/contour_spline.h"  // proto::ContourElement

namespace host {

// How far snapping may move a piece of the curve, um.
static const double kContourSnapToleranceUm = 1.0;

// Puts a degree-2 rational spline with a double knot at every joint into contour form
// when every piece is a straight line or a circular arc within kContourSnapToleranceUm:
// each middle point and weight become the ones the controller computes from the piece's
// end point and height, the corner weights 1.0, the knots 0 0 0 1 1 .. n n n. False, and s
// unchanged, when it is not such a spline (another conic, single knots, too wide an arc).
bool snap_to_contour_form(core::Spline* s);

// The elements that rebuild s exactly (proto::unpack_contour), when s is in contour form;
// nullopt otherwise.
std::optional<std::vector<proto::ContourElement>> contour_elements(const core::Spline& s);

}  // namespace host

#endif  // HOST_LIB_PLAN_CONTOUR_FORM_H
