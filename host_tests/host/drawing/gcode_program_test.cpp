// G-code as CAM programs write it (pcb2gcode, FlatCAM style, written here by hand): dwells,
// tool changes with messages, spindle switching, drilling cycles, units, line numbers; the
// program's operations in file order.
#include <gtest/gtest.h>

#include <cmath>

#include "host/lib/drawing/drawing.h"
#include "host_tests/host/drawing/dxf_builder.h"

namespace host {
namespace {

Drawing import_text(const std::string& name, const std::string& text) {
  return import_drawing(test::write_temp(name, text));
}

std::string refusal(const std::string& name, const std::string& text) {
  try {
    import_text(name, text);
  } catch (const ImportError& e) {
    return e.what();
  }
  return "(accepted)";
}

// Isolation milling the way pcb2gcode writes it: inch, tool change, dwells, two cuts.
const char* kMillInch =
    "( written in the style of pcb2gcode )\n"
    "G94 ( Inches per minute feed rate. )\n"
    "G20 ( Units == INCHES. )\n"
    "G90\n"
    "G00 S10000\n"
    "G64 P0.0004 ( path tolerance: not a dwell )\n"
    "G01 F20.0\n"
    "N10 G00 Z0.5 (Retract to tool change height)\n"
    "T2\n"
    "M5\n"
    "G04 P1.5 (Wait for spindle to stop)\n"
    "(MSG, Change tool bit to mill 0.1mm)\n"
    "M6 (Tool change.)\n"
    "M0 (Temporary machine stop.)\n"
    "M3\n"
    "G04 P2.0\n"
    "G04 P0 ( dwell for no time )\n"
    "G00 Z0.1\n"
    "G00 X0.1 Y0.1\n"
    "G01 Z-0.002 F10\n"
    "G04 P0\n"
    "G01 F20\n"
    "G01 X0.5 Y0.1\n"
    "G01 X0.5 Y0.3\n"
    "G00 Z0.1\n"
    "G00 X1.0 Y0.1\n"
    "G01 Z-0.002\n"
    "G01 X1.0 Y0.2\n"
    "G00 Z0.5\n"
    "M5\n"
    "M9\n"
    "M2\n"
    "%\n";

TEST(GcodeProgram, PcbStyleMillingKeepsItsOperationsInFileOrder) {
  const Drawing d = import_text("mill_inch.ngc", kMillInch);
  EXPECT_EQ(d.units, "inch");
  EXPECT_DOUBLE_EQ(d.unit_to_mm, 25.4);
  ASSERT_EQ(d.curves.size(), 2u);
  ASSERT_EQ(d.program.size(), 8u);
  const ProgramOp* p = d.program.data();
  EXPECT_EQ(p[0].kind, ProgramOp::kSpindle);  // the first M5: the spindle state is now known
  EXPECT_FALSE(p[0].spindle_on);
  EXPECT_EQ(p[1].kind, ProgramOp::kDwell);
  EXPECT_DOUBLE_EQ(p[1].dwell_s, 1.5);  // LinuxCNC: P in seconds
  EXPECT_EQ(p[1].source, "line 11");
  EXPECT_EQ(p[2].kind, ProgramOp::kPause);  // M6 and M0 with nothing between: one stop
  EXPECT_EQ(p[2].text, "Change tool bit to mill 0.1mm");
  EXPECT_NEAR(p[2].z_mm, 12.7, 1e-9);  // the program's tool-change height
  EXPECT_EQ(p[3].kind, ProgramOp::kSpindle);
  EXPECT_TRUE(p[3].spindle_on);
  EXPECT_EQ(p[4].kind, ProgramOp::kDwell);  // G04 P0 is no dwell
  EXPECT_DOUBLE_EQ(p[4].dwell_s, 2.0);
  EXPECT_EQ(p[5].kind, ProgramOp::kCut);
  EXPECT_EQ(p[5].curve, 0);
  EXPECT_NEAR(p[5].depth_mm, -0.0508, 1e-9);
  EXPECT_EQ(p[6].kind, ProgramOp::kCut);
  EXPECT_EQ(p[6].curve, 1);
  EXPECT_EQ(p[7].kind, ProgramOp::kSpindle);
  EXPECT_FALSE(p[7].spindle_on);
  EXPECT_NEAR(p[7].z_mm, 12.7, 1e-9);  // lifted before the spindle stops
  EXPECT_LT((start_point(d.curves[0].spline()) - Point2(2.54, 2.54)).norm(), 1e-9);
  EXPECT_LT((end_point(d.curves[0].spline()) - Point2(12.7, 7.62)).norm(), 1e-9);
  EXPECT_EQ(d.entity_counts.at("pause (M0/M1/M6)"), 1);
  EXPECT_EQ(d.entity_counts.at("dwell (G4)"), 2);
}

TEST(GcodeProgram, UnitsShownAreTheFilesOwn) {
  EXPECT_EQ(import_text("mm.ngc", "G21\nG1 X1\n").units, "mm");
  EXPECT_EQ(import_text("none.ngc", "G1 X1\n").units, "mm (assumed)");
  const Drawing both = import_text("both.ngc", "G20\nG1 X1\nG21\nG1 X30\n");
  EXPECT_NE(both.units.find("inch and mm"), std::string::npos) << both.units;
  EXPECT_DOUBLE_EQ(both.unit_to_mm, 25.4);
  EXPECT_LT((end_point(both.curves[0].spline()) - Point2(30, 0)).norm(), 1e-9);
}

TEST(GcodeProgram, M0WithoutAMessageSaysWhatStoppedAndM1Too) {
  const Drawing d = import_text("stops.ngc", "G21\nG0 X1\nM0\nG0 X2\nM1\nG0 X3\nM6 T4\n");
  ASSERT_EQ(d.program.size(), 3u);
  EXPECT_EQ(d.program[0].text, "Program stop (M0)");
  EXPECT_EQ(d.program[1].text, "Optional stop (M1)");
  EXPECT_EQ(d.program[2].text, "Change tool T4");
  EXPECT_EQ(d.program[2].tool, 4);
}

TEST(GcodeProgram, MessageGoesWithTheNextPauseOnly) {
  const Drawing d =
      import_text("msg.ngc", "G21\n(msg, first)\nG0 X1\nM0\nG0 X2\nM0 (MSG,second )\nG0 X3\nM0\n");
  ASSERT_EQ(d.program.size(), 3u);
  EXPECT_EQ(d.program[0].text, "first");
  EXPECT_EQ(d.program[1].text, "second");
  EXPECT_EQ(d.program[2].text, "Program stop (M0)");
}

// Drilling the way pcb2gcode writes it: G81 with R, Z, F, then bare X Y lines, G80.
TEST(GcodeProgram, AMessageWithoutAStopIsNoted) {
  const Drawing d = import_text("lonely.ngc", "G21\nG1 X1\n(MSG, never shown)\nG1 X2\n");
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("(MSG, never shown) is not followed by a stop"), std::string::npos);
}

TEST(GcodeProgram, G81HolesTakeStickyRAndZInInches) {
  const Drawing d = import_text("drill.ngc",
                                "G94\nG20\nG91.1\nG90\nG00 Z1.0\nG0 Z0.08\n"
                                "G81 R0.08 Z-0.06 F30 X0.9 Y-0.45\nX1.65 Y-0.55\n"
                                "N300 X1.65 Y-0.80\nG80\nG00 Z1.0\nM2\n");
  ASSERT_EQ(d.program.size(), 3u);
  EXPECT_TRUE(d.curves.empty());
  const double in = 25.4;
  const Point2 at[] = {{0.9 * in, -0.45 * in}, {1.65 * in, -0.55 * in}, {1.65 * in, -0.8 * in}};
  for (int i = 0; i < 3; ++i) {
    const ProgramOp& h = d.program[i];
    EXPECT_EQ(h.kind, ProgramOp::kDrill);
    EXPECT_LT((h.at - at[i]).norm(), 1e-9);
    EXPECT_NEAR(h.z_start_mm, 0.08 * in, 1e-9);
    EXPECT_NEAR(h.z_bottom_mm, -0.06 * in, 1e-9);
    EXPECT_NEAR(h.retract_mm, 0.08 * in, 1e-9);  // G98: the start height, here R
    EXPECT_NEAR(h.feed_mm_per_s, 30 * in / 60, 1e-9);
    EXPECT_EQ(h.peck_mm, 0.0);
  }
  EXPECT_EQ(d.program[2].source, "line 9");
  const Extents e = d.extents();  // holes count in the extents
  EXPECT_NEAR(e.width(), 0.75 * in, 1e-9);
}

TEST(GcodeProgram, G98RetractsToTheStartHeightG99ToR) {
  const Drawing d = import_text(
      "retract.ngc", "G21\nG0 Z10\nG98 G81 X1 Y1 R2 Z-1\nX2\nG99 G81 X3 R2 Z-1\nX4\nG80\n");
  ASSERT_EQ(d.program.size(), 4u);
  EXPECT_DOUBLE_EQ(d.program[0].retract_mm, 10.0);
  EXPECT_DOUBLE_EQ(d.program[1].retract_mm, 10.0);
  EXPECT_DOUBLE_EQ(d.program[2].retract_mm, 2.0);
  EXPECT_DOUBLE_EQ(d.program[3].retract_mm, 2.0);
}

TEST(GcodeProgram, G82DwellsAndG83Pecks) {
  const Drawing d = import_text(
      "cycles.ngc", "G21\nG0 Z5\nG82 X1 Y1 R1 Z-2 P0.5 F60\nG83 X2 Y1 R1 Z-3 Q0.8\nG80\n");
  ASSERT_EQ(d.program.size(), 2u);
  EXPECT_DOUBLE_EQ(d.program[0].dwell_s, 0.5);
  EXPECT_DOUBLE_EQ(d.program[0].feed_mm_per_s, 1.0);
  EXPECT_DOUBLE_EQ(d.program[1].peck_mm, 0.8);
  EXPECT_DOUBLE_EQ(d.program[1].dwell_s, 0.0);
}

TEST(GcodeProgram, IncrementalCycleRepeatsWithL) {
  // G91: X/Y steps from the current point, R from the start height, Z from R.
  const Drawing d = import_text("incr.ngc", "G21\nG0 X10 Y10 Z5\nG91 G81 X5 R-3 Z-4 L3\nG80\n");
  ASSERT_EQ(d.program.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(d.program[i].at.x(), 15.0 + 5 * i);
    EXPECT_DOUBLE_EQ(d.program[i].z_start_mm, 2.0);
    EXPECT_DOUBLE_EQ(d.program[i].z_bottom_mm, -2.0);
  }
}

TEST(GcodeProgram, FlatcamStyleToolChangeAndLaterCutsAtTheirDepths) {
  // FlatCAM's default post-processor: T/M6 on one line, its message, dwell after M3.
  const Drawing d = import_text("flatcam.nc",
                                "G21\nG90\nG94\nG01 F120.00\nG00 Z15.0000\nM05\n"
                                "T1\nM6\n(MSG, Change to Tool Dia = 0.2000)\nM0\nG00 Z15.0000\n"
                                "M03\nG4 P1\nG00 X1 Y1\nG01 Z-0.05\nG01 X5 Y1\nG00 Z2\n"
                                "G00 X1 Y3\nG01 Z-0.1\nG01 X5 Y3\nG00 Z15\nM05\n");
  // M6 stops; the message comes after it, with the M0 right behind: one stop, showing it.
  int pauses = 0, cuts = 0;
  for (const ProgramOp& op : d.program) {
    if (op.kind == ProgramOp::kPause) {
      EXPECT_EQ(op.text, "Change to Tool Dia = 0.2000");
      ++pauses;
    }
    if (op.kind == ProgramOp::kCut) {
      EXPECT_NEAR(op.depth_mm, cuts == 0 ? -0.05 : -0.1, 1e-12);
      ++cuts;
    }
  }
  EXPECT_EQ(pauses, 1);
  EXPECT_EQ(cuts, 2);
}

TEST(GcodeProgram, ADepthChangeInsideACutStartsANewCurve) {
  const Drawing d = import_text("passes.ngc", "G21\nG0 Z1\nG1 Z-0.1\nG1 X10\nG1 Z-0.2\nG1 X0\n");
  ASSERT_EQ(d.curves.size(), 2u);
  EXPECT_DOUBLE_EQ(d.program[0].depth_mm, -0.1);
  EXPECT_DOUBLE_EQ(d.program[1].depth_mm, -0.2);
  EXPECT_LT((start_point(d.curves[1].spline()) - Point2(10, 0)).norm(), 1e-12);
}

TEST(GcodeProgram, NoZAtAllLeavesTheDepthToThePlanner) {
  const Drawing d = import_text("noz.ngc", "G21\nG1 X10\n");
  ASSERT_EQ(d.program.size(), 1u);
  EXPECT_TRUE(std::isnan(d.program[0].depth_mm));
}

TEST(GcodeProgram, WordsThatCannotBeHonouredAreRefusedNamingFileAndLine) {
  struct Case {
    const char* text;
    const char* expect;
  };
  const Case cases[] = {
      {"G21\nM7\nM98 P100\n", "line 3: M98 is not supported"},
      {"G21\nG81 X1 Y1 Z-1\n", "line 2: G81 needs R and Z"},
      {"G21\nG83 X1 R1 Z-1\n", "line 2: G83 needs Q > 0"},
      {"G21\nG81 X1 R-1 Z1\n", "line 2: G81 bottom Z 1 mm is above R -1 mm"},
      {"G21\nG81 X1 R1 Z-1\nG80\nX2\n", "line 4: X/Y/Z with no motion mode (after G80)"},
      {"G21\nG4\n", "line 2: G4 without P"},
      {"G21\nG4 P1 X2\n", "line 2: G4 with X/Y/Z words"},
      {"G21\nG28\n", "line 2: G28 is not supported"},
      {"G21\nG43 H1\n", "line 2: word H"},
      {"G21\n#1=2\n", "line 2: parameters and expressions"},
      {"G21\nO100 sub\n", "line 2: O-words"},
      {"G21\nG95\n", "line 2: G95 is not supported"},
  };
  for (const Case& c : cases) {
    const std::string m = refusal("refused.ngc", c.text);
    EXPECT_NE(m.find("refused.ngc: "), std::string::npos) << m;
    EXPECT_NE(m.find(c.expect), std::string::npos) << c.text << " -> " << m;
  }
}

TEST(GcodeProgram, CoolantIsNotedOnceAndLinesAfterM2AreIgnored) {
  const Drawing d = import_text("cool.ngc", "G21\nM8\nG1 X1\nM8\nM2\nG18\n");
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("line 2: M8 (coolant) ignored"), std::string::npos);
}

TEST(GcodeProgram, LaserStyleFilesStillCutOnlyWhileOn) {
  const Drawing d =
      import_text("laser2.ngc", "G21\nG0 X0\nM3 S100\nG1 X10\nM5\nG1 X20\nM3\nG1 X30\n");
  ASSERT_EQ(d.curves.size(), 2u);
  ASSERT_EQ(d.program.size(), 6u);  // on, cut, off, on, cut, and off at the end
  EXPECT_EQ(d.program[1].kind, ProgramOp::kCut);
  EXPECT_EQ(d.program[2].kind, ProgramOp::kSpindle);
}

}  // namespace
}  // namespace host
