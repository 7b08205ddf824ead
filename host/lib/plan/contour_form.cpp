// Contour form of splines (see contour_form.h).
#include "host/lib/plan/contour_form.h"

#include <algorithm>  // std::max
#include <cmath>      // std::sqrt, std::llround, std::fabs, std::hypot

namespace host {

namespace {

// Knot pattern of a contour-shaped spline: index j belongs to corner pattern(j), 0 0 0 1 1
// ... n n n.
int32_t pattern(uint16_t j, uint16_t knot_count) {
  if (j < 3) return 0;
  if (j + 3 >= knot_count) return (knot_count - 4) / 2;
  return (j - 1) / 2;
}

// A point of the rational quadratic (p0, 1), (m, c), (p1, 1) at t, um.
void bezier(const core::ControlPoint& p0, const core::ControlPoint& m, double c,
            const core::ControlPoint& p1, double t, double* x, double* y) {
  const double b0 = (1 - t) * (1 - t), b1 = 2 * t * (1 - t) * c, b2 = t * t;
  const double d = b0 + b1 + b2;
  *x = (b0 * p0.x_um + b1 * m.x_um + b2 * p1.x_um) / d;
  *y = (b0 * p0.y_um + b1 * m.y_um + b2 * p1.y_um) / d;
}

// Largest distance between the two pieces at equal parameters (both with end weights 1,
// so this bounds the distance between the curves).
double piece_distance_um(const core::ControlPoint& p0, const core::ControlPoint& m, double c,
                         const core::ControlPoint& m2, double c2, const core::ControlPoint& p1) {
  double worst = 0;
  for (int i = 1; i < 16; ++i) {
    double x = 0, y = 0, x2 = 0, y2 = 0;
    bezier(p0, m, c, p1, i / 16.0, &x, &y);
    bezier(p0, m2, c2, p1, i / 16.0, &x2, &y2);
    worst = std::max(worst, std::hypot(x - x2, y - y2));
  }
  return worst;
}

// The middle's signed distance from the chord (left > 0) and its position along it, um.
void middle_offsets(const core::ControlPoint& p0, const core::ControlPoint& m,
                    const core::ControlPoint& p1, double* height, double* along, double* chord) {
  const double dx = p1.x_um - p0.x_um, dy = p1.y_um - p0.y_um;
  const double mx = m.x_um - p0.x_um, my = m.y_um - p0.y_um;
  *chord = std::hypot(dx, dy);
  *height = *chord > 0 ? (dx * my - dy * mx) / *chord : 0;
  *along = *chord > 0 ? (dx * mx + dy * my) / *chord : 0;
}

bool same_point(const core::ControlPoint& a, const core::ControlPoint& b) {
  return a.x_um == b.x_um && a.y_um == b.y_um && a.weight_q14 == b.weight_q14;
}

proto::ContourElement element(const core::ControlPoint& p0, const core::ControlPoint& p1, bool arc,
                              int32_t height_um) {
  proto::ContourElement e;
  e.dx_um = p1.x_um - p0.x_um;
  e.dy_um = p1.y_um - p0.y_um;
  e.arc = arc;
  e.height_um = height_um;
  return e;
}

bool contour_knots(const core::Spline& s) {
  if (!proto::is_contour_shape(s)) return false;
  for (uint16_t j = 1; j < s.knot_count; ++j) {
    const bool same = pattern(j, s.knot_count) == pattern(j - 1, s.knot_count);
    if (same ? s.knot[j] != s.knot[j - 1] : s.knot[j] <= s.knot[j - 1]) return false;
  }
  return true;
}

}  // namespace

bool snap_to_contour_form(core::Spline* s) {
  if (!contour_knots(*s)) return false;
  core::Spline out = *s;
  for (uint16_t i = 0; i + 2 < s->control_count; i += 2) {
    const core::ControlPoint& p0 = s->control[i];
    const core::ControlPoint& m = s->control[i + 1];
    const core::ControlPoint& p1 = s->control[i + 2];
    core::ControlPoint q0 = p0;
    q0.weight_q14 = core::kWeightOneQ14;
    double height = 0, along = 0, chord = 0;
    middle_offsets(p0, m, p1, &height, &along, &chord);
    if (chord <= 0) return false;
    proto::ContourElement best{};
    bool found = false;
    if (std::fabs(height) <= kContourSnapToleranceUm && along >= 0 && along <= chord) {
      best = element(p0, p1, false, 0);  // on the chord: the same straight segment
      found = true;
    } else {
      // An arc: the piece with end weights 1 against the arc rebuilt from each nearby height.
      const double c = m.weight_q14 / std::sqrt(static_cast<double>(p0.weight_q14) * p1.weight_q14);
      double best_um = kContourSnapToleranceUm;
      const int64_t h0 = std::llround(height);
      for (int64_t h = h0 - 1; h <= h0 + 1; ++h) {
        const proto::ContourElement e = element(p0, p1, true, static_cast<int32_t>(h));
        core::ControlPoint m2;
        if (proto::contour_middle(q0, e, &m2) != proto::ErrorCode::kOk) continue;
        const double d = piece_distance_um(p0, m, c, m2, m2.weight_q14 / 16384.0, p1);
        if (d <= best_um) best_um = d, best = e, found = true;
      }
    }
    if (!found) return false;
    proto::contour_middle(q0, best, &out.control[i + 1]);
    out.control[i].weight_q14 = core::kWeightOneQ14;
    out.control[i + 2].weight_q14 = core::kWeightOneQ14;
  }
  for (uint16_t j = 0; j < s->knot_count; ++j) out.knot[j] = pattern(j, s->knot_count);
  *s = out;
  return true;
}

std::optional<std::vector<proto::ContourElement>> contour_elements(const core::Spline& s) {
  if (!proto::is_contour_shape(s)) return std::nullopt;
  for (uint16_t j = 0; j < s.knot_count; ++j)
    if (s.knot[j] != pattern(j, s.knot_count)) return std::nullopt;
  if (s.control[0].weight_q14 != core::kWeightOneQ14) return std::nullopt;
  std::vector<proto::ContourElement> out;
  for (uint16_t i = 0; i + 2 < s.control_count; i += 2) {
    const core::ControlPoint& p0 = s.control[i];
    const core::ControlPoint& p1 = s.control[i + 2];
    if (p1.weight_q14 != core::kWeightOneQ14) return std::nullopt;
    double height = 0, along = 0, chord = 0;
    middle_offsets(p0, s.control[i + 1], p1, &height, &along, &chord);
    // A line, else the arc of a height next to the middle's distance from the chord.
    const int64_t h0 = std::llround(height);
    std::vector<proto::ContourElement> tries = {element(p0, p1, false, 0)};
    for (int64_t h = h0 - 1; h <= h0 + 1; ++h)
      tries.push_back(element(p0, p1, true, static_cast<int32_t>(h)));
    bool found = false;
    for (const proto::ContourElement& e : tries) {
      core::ControlPoint m;
      if (!found && proto::contour_middle(p0, e, &m) == proto::ErrorCode::kOk &&
          same_point(m, s.control[i + 1])) {
        out.push_back(e);
        found = true;
      }
    }
    if (!found) return std::nullopt;
  }
  return out;
}

}  // namespace host
