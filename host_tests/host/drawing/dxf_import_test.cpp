// DXF import of well-formed drawings: every entity type, units, blocks.
#include <gtest/gtest.h>

#include <cmath>

#include "host/lib/drawing/drawing.h"
#include "host_tests/host/drawing/dxf_builder.h"
#include "host_tests/host/drawing/eigen_reference.h"

namespace host {
namespace {

using test::dxf_text;
using test::Groups;
using test::spline_entity;
using test::write_temp;

const double kPi = 3.14159265358979323846;

Drawing import_text(const std::string& name, const std::string& text) {
  return import_drawing(write_temp(name, text));
}

double radius_error(const BSpline& s, const Point2& c, double r) {
  double worst = 0;
  for (int i = 0; i <= 400; ++i) {
    const double t = s.t_min() + (s.t_max() - s.t_min()) * i / 400.0;
    worst = std::max(worst, std::fabs((evaluate(s, t) - c).norm() - r));
  }
  return worst;
}

std::string line_entity(double x1, double y1, double x2, double y2) {
  return Groups().g(0, "LINE").g(5, "1F").g(8, "0").pt(10, x1, y1).pt(11, x2, y2).str();
}

TEST(DxfImport, LineBecomesDegreeOneSplineInMm) {
  const Drawing d = import_text("line.dxf", dxf_text(line_entity(1, 2, 11, 2)));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_EQ(d.curves[0].spline().degree, 1);
  EXPECT_STREQ(d.curves[0].kind, "LINE");
  EXPECT_NE(d.curves[0].source.find("handle 1F"), std::string::npos);
  EXPECT_LT((end_point(d.curves[0].spline()) - Point2(11, 2)).norm(), 1e-12);
  EXPECT_EQ(d.units, "mm");
  EXPECT_TRUE(d.warnings.empty());
}

// LINEs that continue one another in the file (each starts where the previous one ended,
// as CAD programs and tracers write a contour) are one polyline; a gap, a LINE drawn the
// other way or another entity between them starts a new curve.
TEST(DxfImport, ChainedLinesBecomeOnePolyline) {
  const std::string point = Groups().g(0, "POINT").g(8, "0").pt(10, 6, 0).str();
  const std::string e = line_entity(0, 0, 1, 0) + line_entity(1, 0, 1, 1) +
                        line_entity(1, 1, 0, 1) + line_entity(0, 1, 0, 0) +  // closed square
                        line_entity(5, 0, 6, 0) +                            // after a gap
                        line_entity(7, 0, 6, 0) +                            // drawn the other way
                        point + line_entity(6, 0, 6, 5);  // continues, but a POINT comes first
  const Drawing d = import_text("chain.dxf", dxf_text(e));
  ASSERT_EQ(d.curves.size(), 4u);
  const BSpline square = d.curves[0].spline();
  EXPECT_EQ(square.degree, 1);
  const std::vector<Point2> corners = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  ASSERT_EQ(square.control.size(), corners.size());
  for (size_t i = 0; i < corners.size(); ++i) EXPECT_EQ(square.control[i], corners[i]) << i;
  EXPECT_EQ(square.knots, (std::vector<double>{0, 0, 1, 2, 3, 4, 4}));
  EXPECT_EQ(check_bspline(square), "");
  EXPECT_STREQ(d.curves[0].kind, "LINE");
  EXPECT_NE(d.curves[0].source.find("LINE #1 ("), std::string::npos) << d.curves[0].source;
  EXPECT_NE(d.curves[0].source.find("and the 3 LINEs that continue it, to #4 (line "),
            std::string::npos)
      << d.curves[0].source;
  for (size_t c = 1; c < 4; ++c) {
    EXPECT_EQ(d.curves[c].spline().control.size(), 2u) << c;
    EXPECT_EQ(d.curves[c].source.find("continue"), std::string::npos) << d.curves[c].source;
  }
  EXPECT_EQ(d.curves[3].spline().control[1], Point2(6, 5));
}

// In a block the chain is the block's own: inserted, it is one curve; model-space LINEs
// around the block definition do not join it.
TEST(DxfImport, ChainedLinesInABlockStayInTheBlock) {
  Groups b;
  b.g(0, "BLOCK").g(8, "0").g(2, "B").g(70, 0).pt(10, 0, 0).g(3, "B");
  const std::string blocks = b.str() + line_entity(1, 1, 3, 1) + line_entity(3, 1, 3, 2) +
                             Groups().g(0, "ENDBLK").g(8, "0").str();
  const std::string ins =
      Groups().g(0, "INSERT").g(5, "90").g(8, "0").g(2, "B").pt(10, 10, 0).str();
  const Drawing d =
      import_text("chain_block.dxf", dxf_text(line_entity(3, 2, 4, 2) + ins, 4, blocks));
  ASSERT_EQ(d.curves.size(), 2u);
  size_t chained = d.curves[0].spline().control.size() == 3 ? 0 : 1;
  ASSERT_EQ(d.curves[chained].spline().control.size(), 3u);
  EXPECT_EQ(d.curves[chained].spline().control[2], Point2(13, 2));
  EXPECT_NE(d.curves[chained].source.find("and the LINE that continues it, #2 (line "),
            std::string::npos)
      << d.curves[chained].source;
  EXPECT_EQ(d.curves[1 - chained].spline().control.size(), 2u);
}

struct UnitCase {
  int insunits;
  double mm_per_unit;
  const char* name;  // Drawing::units
};

class DxfUnits : public testing::TestWithParam<UnitCase> {};

TEST_P(DxfUnits, CoordinatesAreConvertedToMm) {
  const Drawing d =
      import_text("units.dxf", dxf_text(line_entity(0, 0, 2, 0), GetParam().insunits));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_NEAR(end_point(d.curves[0].spline()).x(), 2 * GetParam().mm_per_unit, 1e-12);
  EXPECT_EQ(d.units, GetParam().name);
}

// Every unit docs/user-guide.md lists.
INSTANTIATE_TEST_SUITE_P(EveryUnit, DxfUnits,
                         testing::Values(UnitCase{4, 1.0, "mm"}, UnitCase{5, 10.0, "cm"},
                                         UnitCase{6, 1000.0, "m"}, UnitCase{1, 25.4, "inch"},
                                         UnitCase{2, 304.8, "foot"},
                                         UnitCase{8, 25.4e-6, "microinch"},
                                         UnitCase{9, 0.0254, "mil"}, UnitCase{13, 0.001, "micron"},
                                         UnitCase{14, 100.0, "dm"}),
                         [](const testing::TestParamInfo<UnitCase>& i) {
                           return "Insunits" + std::to_string(i.param.insunits);
                         });

TEST(DxfImport, MissingInsunitsMeansMmWithAWarning) {
  const Drawing d = import_text("nounits.dxf", dxf_text(line_entity(0, 0, 2, 0), -1));
  EXPECT_EQ(d.units, "mm (assumed)");
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("no $INSUNITS"), std::string::npos);
}

TEST(DxfImport, UnitlessInsunitsMeansMmWithAWarning) {
  const Drawing d = import_text("unitless.dxf", dxf_text(line_entity(0, 0, 2, 0), 0));
  EXPECT_EQ(d.units, "mm (assumed)");
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("unitless"), std::string::npos);
}

TEST(DxfImport, UnsupportedUnitIsRefusedWithItsCode) {
  try {
    import_text("parsec.dxf", dxf_text(line_entity(0, 0, 2, 0), 20));
    FAIL() << "no error";
  } catch (const ImportError& e) {
    // The whole message after the file's (temporary) folder.
    const std::string m = e.what();
    EXPECT_NE(m.find("parsec.dxf: $INSUNITS 20 is a unit this tool does not convert (supported: "
                     "0 unitless = mm, 1 inch, 2 foot, 4 mm, 5 cm, 6 m, 8 microinch, 9 mil, "
                     "13 micron, 14 dm)"),
              std::string::npos)
        << m;
  }
}

TEST(DxfImport, ArcCrossingZeroDegreesIsAnExactRationalArc) {
  const std::string arc = Groups()
                              .g(0, "ARC")
                              .g(5, "30")
                              .g(8, "0")
                              .pt(10, 5, 5)
                              .g(40, 2.0)
                              .g(50, 300.0)
                              .g(51, 60.0)
                              .str();
  const Drawing d = import_text("arc.dxf", dxf_text(arc));
  ASSERT_EQ(d.curves.size(), 1u);
  const BSpline s = d.curves[0].spline();
  EXPECT_TRUE(s.rational());
  EXPECT_EQ(s.control.size(), 5u);  // 120 degrees: two pieces
  EXPECT_LT(radius_error(s, {5, 5}, 2.0), 1e-12);
  EXPECT_LT(
      (start_point(s) - Point2(5 + 2 * std::cos(-kPi / 3), 5 + 2 * std::sin(-kPi / 3))).norm(),
      1e-12);
  // Counter-clockwise through 0 degrees, i.e. through (7, 5).
  EXPECT_LT((evaluate(s, 0.5 * (s.t_min() + s.t_max())) - Point2(7, 5)).norm(), 1e-9);
}

TEST(DxfImport, CircleIsClosedAndExact) {
  const std::string c = Groups().g(0, "CIRCLE").g(5, "31").g(8, "0").pt(10, -3, 4).g(40, 1.5).str();
  const Drawing d = import_text("circle.dxf", dxf_text(c));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_LT(radius_error(d.curves[0].spline(), {-3, 4}, 1.5), 1e-12);
  const Extents e = d.extents();
  EXPECT_NEAR(e.min.x(), -4.5, 1e-6);
  EXPECT_NEAR(e.max.y(), 5.5, 1e-6);
}

TEST(DxfImport, CircleSeenFromBelowIsMirroredInX) {
  const std::string c = Groups()
                            .g(0, "CIRCLE")
                            .g(8, "0")
                            .pt(10, 3, 4)
                            .g(40, 1.0)
                            .g(210, 0.0)
                            .g(220, 0.0)
                            .g(230, -1.0)
                            .str();
  const Drawing d = import_text("circle_below.dxf", dxf_text(c));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_LT(radius_error(d.curves[0].spline(), {-3, 4}, 1.0), 1e-12);
}

TEST(DxfImport, EllipseArcIsExact) {
  // Centre (10,10), major axis (0,6) (vertical), ratio 0.5, parameters 0..pi.
  const std::string e = Groups()
                            .g(0, "ELLIPSE")
                            .g(8, "0")
                            .pt(10, 10, 10)
                            .pt(11, 0, 6)
                            .g(40, 0.5)
                            .g(41, 0.0)
                            .g(42, kPi)
                            .str();
  const Drawing d = import_text("ellipse.dxf", dxf_text(e));
  ASSERT_EQ(d.curves.size(), 1u);
  const BSpline s = d.curves[0].spline();
  EXPECT_LT((start_point(s) - Point2(10, 16)).norm(), 1e-12);
  EXPECT_LT((end_point(s) - Point2(10, 4)).norm(), 1e-12);
  // Minor axis = z x major * ratio = (-6, 0) * 0.5: the half ellipse bulges to x = 7.
  EXPECT_LT((evaluate(s, 0.5 * (s.t_min() + s.t_max())) - Point2(7, 10)).norm(), 1e-9);
}

TEST(DxfImport, LwpolylineWithBulgeAndClosedFlag) {
  // Square 10 x 10 whose top edge, from (10,10) to (0,10), is a counter-clockwise half
  // circle (bulge +1): it bulges upwards, to y = 15.
  const std::string p = Groups()
                            .g(0, "LWPOLYLINE")
                            .g(5, "40")
                            .g(8, "0")
                            .g(90, 4)
                            .g(70, 1)
                            .g(10, 0.0)
                            .g(20, 0.0)
                            .g(10, 10.0)
                            .g(20, 0.0)
                            .g(10, 10.0)
                            .g(20, 10.0)
                            .g(42, 1.0)
                            .g(10, 0.0)
                            .g(20, 10.0)
                            .str();
  const Drawing d = import_text("lwpoly.dxf", dxf_text(p));
  ASSERT_EQ(d.curves.size(), 1u);
  const Extents e = d.extents();
  EXPECT_NEAR(e.max.y(), 15.0, 1e-6);  // half circle of radius 5 above y = 10
  EXPECT_LT((end_point(d.curves[0].spline()) - Point2(0, 0)).norm(), 1e-12);  // closed
}

TEST(DxfImport, OldStylePolylineWithVertices) {
  const std::string p = Groups()
                            .g(0, "POLYLINE")
                            .g(8, "0")
                            .g(66, 1)
                            .g(70, 0)
                            .g(0, "VERTEX")
                            .g(8, "0")
                            .pt(10, 0, 0)
                            .g(0, "VERTEX")
                            .g(8, "0")
                            .pt(10, 4, 0)
                            .g(42, 1.0)
                            .g(0, "VERTEX")
                            .g(8, "0")
                            .pt(10, 8, 0)
                            .g(0, "SEQEND")
                            .g(8, "0")
                            .str();
  const Drawing d = import_text("poly.dxf", dxf_text(p));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_STREQ(d.curves[0].kind, "POLYLINE");
  EXPECT_NEAR(d.extents().min.y(), -2.0, 1e-6);  // CCW half circle from (4,0) to (8,0)
}

TEST(DxfImport, RationalSplineKeepsItsWeights) {
  const double w = std::sqrt(0.5);
  const std::string s =
      spline_entity(2, {0, 0, 0, 1, 1, 1}, {{1, 0}, {1, 1}, {0, 1}}, {1, w, 1}, 8 | 4);
  const Drawing d = import_text("rational.dxf", dxf_text(s));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_TRUE(d.curves[0].spline().rational());
  EXPECT_LT(radius_error(d.curves[0].spline(), {0, 0}, 1.0), 1e-12);  // quarter circle
}

TEST(DxfImport, NegativeKnotRangeIsEvaluatedAsGiven) {
  const std::vector<double> knots = {-10, -10, -10, -10, -4, -3, -3, -3, -3};
  const std::vector<std::pair<double, double>> ctrl = {{0, 0}, {1, 3}, {4, 4}, {6, 1}, {8, 0}};
  const Drawing d = import_text("negknots.dxf", dxf_text(spline_entity(3, knots, ctrl)));
  ASSERT_EQ(d.curves.size(), 1u);
  const BSpline s = d.curves[0].spline();
  EXPECT_EQ(s.t_min(), -10);
  EXPECT_EQ(s.t_max(), -3);
  EXPECT_LT((evaluate(s, -5.5) - test::eigen_point(s, -5.5)).norm(), 1e-12);
}

TEST(DxfImport, PeriodicClosedSplineWithUnclampedKnotsIsDrawnAsStored) {
  // Uniform cubic over a square's corners wrapped by 3: a closed smooth loop.
  std::vector<std::pair<double, double>> ctrl = {{0, 0}, {10, 0}, {10, 10}, {0, 10},
                                                 {0, 0}, {10, 0}, {10, 10}};
  std::vector<double> knots;
  for (int i = 0; i < 11; ++i) knots.push_back(i);
  const Drawing d =
      import_text("periodic.dxf", dxf_text(spline_entity(3, knots, ctrl, {}, 8 | 2 | 1)));
  ASSERT_EQ(d.curves.size(), 1u);
  const BSpline s = d.curves[0].spline();
  EXPECT_LT((start_point(s) - end_point(s)).norm(), 1e-12);
  EXPECT_TRUE(d.warnings.empty());
}

TEST(DxfImport, ClosedFlagOnAnOpenSplineIsReported) {
  const std::string s = spline_entity(1, {0, 0, 1, 1}, {{0, 0}, {5, 0}}, {}, 1);
  const Drawing d = import_text("notclosed.dxf", dxf_text(s));
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("flagged closed but its ends are 5 apart"), std::string::npos);
}

TEST(DxfImport, FitPointOnlySplineIsInterpolatedThroughItsFitPoints) {
  Groups g;
  g.g(0, "SPLINE").g(5, "77").g(8, "0").g(70, 8).g(71, 3).g(72, 0).g(73, 0).g(74, 5);
  const std::vector<Point2> fit = {{0, 0}, {5, 3}, {10, 0}, {15, -3}, {20, 0}};
  for (const Point2& p : fit) g.pt(11, p.x(), p.y());
  const Drawing d = import_text("fit.dxf", dxf_text(g.str()));
  ASSERT_EQ(d.curves.size(), 1u);
  const std::vector<Point2> pts = sample(d.curves[0].spline(), 1e-5);
  for (const Point2& f : fit) {
    double best = 1e300;
    for (const Point2& p : pts) best = std::min(best, (p - f).norm());
    EXPECT_LT(best, 1e-4) << f.transpose();
  }
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("fit points only"), std::string::npos);
}

TEST(DxfImport, InsertAppliesScaleRotationAndBasePoint) {
  // Block "B" with base (1,1) holds a line (1,1)-(3,1). Inserted at (10,20), scale (2,3),
  // rotation 90: (p - base) scaled -> (0,0)-(4,0), rotated -> (0,0)-(0,4), moved ->
  // (10,20)-(10,24).
  Groups b;
  b.g(0, "BLOCK").g(8, "0").g(2, "B").g(70, 0).pt(10, 1, 1).g(3, "B");
  const std::string blocks =
      b.str() + line_entity(1, 1, 3, 1) + Groups().g(0, "ENDBLK").g(8, "0").str();
  const std::string ins = Groups()
                              .g(0, "INSERT")
                              .g(5, "90")
                              .g(8, "0")
                              .g(2, "B")
                              .pt(10, 10, 20)
                              .g(41, 2.0)
                              .g(42, 3.0)
                              .g(50, 90.0)
                              .str();
  const Drawing d = import_text("insert.dxf", dxf_text(ins, 4, blocks));
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_LT((start_point(d.curves[0].spline()) - Point2(10, 20)).norm(), 1e-12);
  EXPECT_LT((end_point(d.curves[0].spline()) - Point2(10, 24)).norm(), 1e-12);
  EXPECT_NE(d.curves[0].source.find("via INSERT #1 of 'B'"), std::string::npos)
      << d.curves[0].source;
}

TEST(DxfImport, InsertOfAMissingBlockIsRefused) {
  const std::string ins =
      Groups().g(0, "INSERT").g(5, "91").g(8, "0").g(2, "NOPE").pt(10, 0, 0).str();
  try {
    import_text("noblock.dxf", dxf_text(ins));
    FAIL() << "no error";
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("block 'NOPE', which the file does not define"),
              std::string::npos)
        << e.what();
  }
}

TEST(DxfImport, TextIsCountedAndReportedNotEngraved) {
  const std::string t = Groups().g(0, "TEXT").g(8, "0").pt(10, 0, 0).g(40, 2.0).g(1, "hello").str();
  const Drawing d = import_text("text.dxf", dxf_text(t + line_entity(0, 0, 1, 0)));
  EXPECT_EQ(d.curves.size(), 1u);
  EXPECT_EQ(d.entity_counts.at("TEXT"), 1);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("1 TEXT entity not engraved"), std::string::npos) << d.warnings[0];
}

}  // namespace
}  // namespace host
