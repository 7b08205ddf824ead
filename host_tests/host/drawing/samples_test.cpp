// The bundled sample imports as documented; the third-party drawings in ../shared/samples
// (next to the repository, when present) import or are refused with a precise message.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "host/lib/drawing/drawing.h"

namespace host {
namespace {

// ../shared seen from the repository top (a sibling of the checkout).
const std::string kShared = std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/";

bool exists(const std::string& p) {
  struct stat st;
  return stat(p.c_str(), &st) == 0;
}

// Skips the test when the shared samples are not on this machine.
#define REQUIRE_SHARED(file) \
  if (!exists(kShared + file)) GTEST_SKIP() << kShared << file << " not present"

std::string refusal(const std::string& path) {
  try {
    import_drawing(path);
  } catch (const ImportError& e) {
    return e.what();
  }
  return "";
}

TEST(BundledSample, EngraverWordImportsInMm) {
  const Drawing d = import_drawing(std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf");
  EXPECT_EQ(d.units, "mm");
  EXPECT_TRUE(d.warnings.empty());
  EXPECT_EQ(d.entity_counts.at("SPLINE"), 12);  // letter outlines and counters
  EXPECT_EQ(d.entity_counts.at("CIRCLE"), 4);   // mounting holes
  EXPECT_EQ(d.entity_counts.at("LWPOLYLINE"), 1);
  ASSERT_EQ(d.curves.size(), 17u);
  const Extents e = d.extents();
  EXPECT_NEAR(e.width(), 124.0, 1e-6);  // the plate
  EXPECT_NEAR(e.height(), 30.0, 1e-6);
}

TEST(SharedSamples, InkscapeBezierSplines) {
  REQUIRE_SHARED("inkscape_r14_bezier_splines_genshi.dxf");
  const Drawing d = import_drawing(kShared + "inkscape_r14_bezier_splines_genshi.dxf");
  EXPECT_EQ(d.entity_counts.at("SPLINE"), 12);
  EXPECT_EQ(d.entity_counts.at("LWPOLYLINE"), 3);
  EXPECT_EQ(d.curves.size(), 14u);  // the 1-vertex LWPOLYLINE draws nothing
  EXPECT_EQ(d.units, "mm (assumed)");
  bool reported = false;
  for (const std::string& w : d.warnings)
    reported = reported || w.find("1 vertices") != std::string::npos;
  EXPECT_TRUE(reported);
}

TEST(SharedSamples, LibrecadQuadraticSplinesCirclesArcs) {
  REQUIRE_SHARED("librecad_kin116_quadratic_splines_circle_arc.dxf");
  const Drawing d = import_drawing(kShared + "librecad_kin116_quadratic_splines_circle_arc.dxf");
  EXPECT_EQ(d.entity_counts.at("SPLINE"), 2);
  EXPECT_EQ(d.entity_counts.at("LINE"), 13);
  EXPECT_EQ(d.entity_counts.at("CIRCLE"), 2);
  EXPECT_EQ(d.entity_counts.at("ARC"), 2);
  EXPECT_EQ(d.curves.size(), 19u);
  EXPECT_EQ(d.units, "mm (assumed)");
}

TEST(SharedSamples, DxfParserRationalCircles) {
  REQUIRE_SHARED("dxfparser_arcs_as_rational_splines.dxf");
  const Drawing d = import_drawing(kShared + "dxfparser_arcs_as_rational_splines.dxf");
  ASSERT_EQ(d.curves.size(), 3u);
  // The first two are full circles: closed, every point at one distance from the centre.
  for (int c = 0; c < 2; ++c) {
    const BSpline s = d.curves[c].spline();
    EXPECT_TRUE(s.rational());
    EXPECT_LT((start_point(s) - end_point(s)).norm(), 1e-9);
    const Point2 centre = 0.5 * (evaluate(s, s.t_min() + 0.25 * (s.t_max() - s.t_min())) +
                                 evaluate(s, s.t_min() + 0.75 * (s.t_max() - s.t_min())));
    const double r = (start_point(s) - centre).norm();
    for (int i = 0; i <= 100; ++i) {
      const Point2 p = evaluate(s, s.t_min() + (s.t_max() - s.t_min()) * i / 100.0);
      EXPECT_NEAR((p - centre).norm(), r, 1e-6 * r);
    }
  }
}

TEST(SharedSamples, ViaconstructorGcodeImportsItsArcs) {
  REQUIRE_SHARED("viaconstructor_check_laser_g2g3.ngc");
  const Drawing d = import_drawing(kShared + "viaconstructor_check_laser_g2g3.ngc");
  EXPECT_EQ(d.format, "G-code");
  EXPECT_EQ(d.curves.size(), 4u);  // four laser-on runs (M03 ... M05)
}

TEST(SharedSamples, Pcb2gcodeMillingIsInchWithAToolChangeStopAndDwells) {
  REQUIRE_SHARED("pcb2gcode_example_board_back.ngc");
  const Drawing d = import_drawing(kShared + "pcb2gcode_example_board_back.ngc");
  EXPECT_EQ(d.units, "inch");
  EXPECT_EQ(d.entity_counts.at("pause (M0/M1/M6)"), 1);  // M6 + M0: one stop
  EXPECT_EQ(d.entity_counts.at("dwell (G4)"), 3);        // the G04 P0 ones are no dwell
  ASSERT_FALSE(d.program.empty());
  bool message = false;
  for (const ProgramOp& op : d.program)
    message = message || (op.kind == ProgramOp::kPause &&
                          op.text.find("Change tool bit to mill") != std::string::npos);
  EXPECT_TRUE(message);
  EXPECT_GT(d.curves.size(), 5u);
}

TEST(SharedSamples, Pcb2gcodeDrillingHasItsHolesInOrder) {
  REQUIRE_SHARED("pcb2gcode_example_board_drill.ngc");
  const Drawing d = import_drawing(kShared + "pcb2gcode_example_board_drill.ngc");
  std::vector<Point2> holes;
  for (const ProgramOp& op : d.program)
    if (op.kind == ProgramOp::kDrill) holes.push_back(op.at);
  ASSERT_EQ(holes.size(), 3u);
  EXPECT_LT((holes[0] - Point2(0.9 * 25.4, -0.45 * 25.4)).norm(), 1e-9);
  EXPECT_LT((holes[2] - Point2(1.65 * 25.4, -0.8 * 25.4)).norm(), 1e-9);
}

TEST(SharedSamples, GerberAsADrawingIsSentToTheBoardCommands) {
  REQUIRE_SHARED("kicad519_D1MiniGSR-F_Cu.gbr");
  const std::string m = refusal(kShared + "kicad519_D1MiniGSR-F_Cu.gbr");
  EXPECT_NE(m.find("kicad519_D1MiniGSR-F_Cu.gbr: this is a Gerber (RS-274X)"), std::string::npos)
      << m;
  EXPECT_NE(m.find("`engraver board`, `run`, `send` and `points` plan its isolation"),
            std::string::npos)
      << m;
}

TEST(SharedSamples, ExcellonAsADrawingIsSentToTheBoardCommands) {
  REQUIRE_SHARED("kicad519_D1MiniGSR-PTH.drl");
  const std::string m = refusal(kShared + "kicad519_D1MiniGSR-PTH.drl");
  EXPECT_NE(m.find("kicad519_D1MiniGSR-PTH.drl: this is an Excellon drill file"), std::string::npos)
      << m;
}

}  // namespace
}  // namespace host
