// Contour form: a spline of lines and circular arcs joined at corners is converted into
// exactly what the controller rebuilds from #Q frames (end points and arc heights), within
// a micrometre of the curve; any other spline is left as it was.
#include "host/lib/plan/contour_form.h"

#include <gtest/gtest.h>

#include <cmath>   // std::cos, std::sin, std::hypot
#include <random>  // std::mt19937

#include "host/lib/plan/firmware_spline.h"
#include "host_tests/core/spline_equality.h"

namespace host {
namespace {

const double kPi = 3.14159265358979323846;

// Pieces joined at corners, as the PCB fitter makes them: each line a straight Bezier, each
// arc (centre, radius, start angle, sweep <= 90 degrees) with middle weight cos(sweep / 2).
struct Builder {
  BSpline s;
  explicit Builder(Point2 start) {
    s.degree = 2;
    s.control = {start};
    s.weights = {1.0};
    s.knots = {0, 0, 0};
  }
  void piece(Point2 mid, double w, Point2 end) {
    const double t = s.knots.back() + (end - s.control.back()).norm() + 1e-3;
    s.control.push_back(mid);
    s.weights.push_back(w);
    s.control.push_back(end);
    s.weights.push_back(1.0);
    s.knots.push_back(t);
    s.knots.push_back(t);
  }
  void line(Point2 end) { piece(0.5 * (s.control.back() + end), 1.0, end); }
  void arc(Point2 centre, double r, double a0, double sweep) {
    const double am = a0 + sweep / 2, rm = r / std::cos(sweep / 2);
    piece(centre + rm * Point2(std::cos(am), std::sin(am)), std::cos(sweep / 2),
          centre + r * Point2(std::cos(a0 + sweep), std::sin(a0 + sweep)));
  }
  BSpline done() {
    s.knots.push_back(s.knots.back());
    return s;
  }
};

// A 6 x 3 mm rectangle with 0.4 mm rounded corners, from (10.4, 10) mm anticlockwise.
BSpline rounded_rectangle() {
  const double r = 0.4;
  Builder b(Point2(10 + r, 10));
  b.line(Point2(16 - r, 10));
  b.arc(Point2(16 - r, 10 + r), r, -kPi / 2, kPi / 2);
  b.line(Point2(16, 13 - r));
  b.arc(Point2(16 - r, 13 - r), r, 0, kPi / 2);
  b.line(Point2(10 + r, 13));
  b.arc(Point2(10 + r, 13 - r), r, kPi / 2, kPi / 2);
  b.line(Point2(10, 10 + r));
  b.arc(Point2(10 + r, 10 + r), r, kPi, kPi / 2);
  return b.done();
}

// The distance from p (mm) to the rounded rectangle's outline, um.
double off_rounded_rectangle_um(Point2 p) {
  const double r = 0.4;
  const double cx = std::min(std::max(p.x(), 10 + r), 16 - r);
  const double cy = std::min(std::max(p.y(), 10 + r), 13 - r);
  return std::fabs((p - Point2(cx, cy)).norm() - r) * 1000;
}

// The controller's spline from the elements, as unpack_contour builds it.
core::Spline rebuilt(const core::Spline& s, const std::vector<proto::ContourElement>& els) {
  core::Spline out = s;
  for (size_t i = 0; i < els.size(); ++i) {
    const core::ControlPoint& p0 = out.control[2 * i];
    EXPECT_EQ(proto::contour_middle(p0, els[i], &out.control[2 * i + 1]), proto::ErrorCode::kOk);
    out.control[2 * i + 2] = {p0.x_um + els[i].dx_um, p0.y_um + els[i].dy_um, 16384};
  }
  return out;
}

TEST(ContourForm, LinesAndArcsAreConvertedToWhatTheControllerRebuilds) {
  const std::vector<core::Spline> fw = to_firmware_splines(rounded_rectangle());
  ASSERT_EQ(fw.size(), 1u);
  const auto els = contour_elements(fw[0]);
  ASSERT_TRUE(els.has_value());
  ASSERT_EQ(els->size(), 8u);
  int arcs = 0;
  for (const proto::ContourElement& e : *els) arcs += e.arc;
  EXPECT_EQ(arcs, 4);
  test::expect_same_spline(fw[0], rebuilt(fw[0], *els));
  for (int j = 0; j < fw[0].knot_count; ++j)
    EXPECT_EQ(fw[0].knot[j], j < 3 ? 0 : j + 3 >= fw[0].knot_count ? 8 : (j - 1) / 2);
  // Within a micrometre of the true outline (rounding of ends, middles and weights).
  for (const Point2& p : sample(from_firmware_spline(fw[0]), 0.0001))
    EXPECT_LT(off_rounded_rectangle_um(p), 1.0);
}

TEST(ContourForm, ArcsOfManySizesAreSnappedWithinTheTolerance) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int snapped = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    const double r = 0.02 + u(rng) * 8;
    const Point2 c(50 + u(rng) * 100, 50 + u(rng) * 100);
    const double a0 = u(rng) * 2 * kPi, sweep = (u(rng) < 0.5 ? -1 : 1) * (0.05 + u(rng) * 1.5);
    Builder b(c + r * Point2(std::cos(a0), std::sin(a0)));
    b.arc(c, r, a0, sweep);
    const std::vector<core::Spline> fw = to_firmware_splines(b.done());
    ASSERT_EQ(fw.size(), 1u);
    snapped += contour_elements(fw[0]).has_value();
    double worst_um = 0;
    for (const Point2& p : sample(from_firmware_spline(fw[0]), 0.0001))
      worst_um = std::max(worst_um, std::fabs((p - c).norm() - r) * 1000);
    EXPECT_LT(worst_um, 1.0);
  }
  EXPECT_EQ(snapped, 300);
}

TEST(ContourForm, OtherConicsAndSmoothJointsAreLeftAsTheyWere) {
  // An ellipse piece: middle weight 0.5 where a circle through the same points needs 0.707.
  Builder e(Point2(10, 10));
  e.piece(Point2(12, 10), 0.5, Point2(12, 12));
  const core::Spline ellipse = to_firmware_splines(e.done())[0];
  EXPECT_FALSE(contour_elements(ellipse).has_value());
  core::Spline s = ellipse;
  EXPECT_FALSE(snap_to_contour_form(&s));
  test::expect_same_spline(ellipse, s);
  // Two arcs joined by a single knot (tangent): not the contour form.
  BSpline c1;
  c1.degree = 2;
  c1.control = {Point2(0, 0), Point2(1, 0), Point2(2, 1), Point2(3, 1)};
  c1.weights = {1, 0.9, 0.9, 1};
  c1.knots = {0, 0, 0, 1, 2, 2, 2};
  EXPECT_FALSE(contour_elements(to_firmware_splines(c1)[0]).has_value());
}

}  // namespace
}  // namespace host
