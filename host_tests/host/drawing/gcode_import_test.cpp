// G-code import: feed moves become curves (lines and exact arcs), rapids separate them.
#include <gtest/gtest.h>

#include <cmath>

#include "host/lib/drawing/drawing.h"
#include "host/lib/drawing/gcode_import.h"
#include "host_tests/host/drawing/dxf_builder.h"

namespace host {
namespace {

// Through a file and import_drawing(), as the tool reads it.
Drawing import_via_file(const std::string& name, const std::string& text) {
  return import_drawing(test::write_temp(name, text));
}

TEST(GcodeImport, FeedRunsBetweenRapidsBecomeOneCurveEach) {
  const Drawing d = import_via_file("two.ngc",
                                    "G21 G90\nG0 X0 Y0\nG1 X10 Y0 F100\nG1 X10 Y5\n"
                                    "G0 X20 Y0\nG1 X30 Y0\nM2\n");
  ASSERT_EQ(d.curves.size(), 2u);
  EXPECT_EQ(d.curves[0].spline().degree, 1);
  EXPECT_LT((end_point(d.curves[0].spline()) - Point2(10, 5)).norm(), 1e-12);
  EXPECT_LT((start_point(d.curves[1].spline()) - Point2(20, 0)).norm(), 1e-12);
}

TEST(GcodeImport, ClockwiseArcWithIjIsExact) {
  // G2 from (10,0) around (0,0) to (0,-10): a clockwise quarter.
  const Drawing d = import_via_file("arc.ngc", "G21\nG0 X10 Y0\nG2 X0 Y-10 I-10 J0\n");
  ASSERT_EQ(d.curves.size(), 1u);
  const BSpline s = d.curves[0].spline();
  for (int i = 0; i <= 100; ++i) {
    const Point2 p = evaluate(s, s.t_min() + (s.t_max() - s.t_min()) * i / 100.0);
    EXPECT_NEAR(p.norm(), 10.0, 1e-9);
    EXPECT_GE(p.x(), -1e-9);  // the short way, through the fourth quadrant
    EXPECT_LE(p.y(), 1e-9);
  }
}

TEST(GcodeImport, FullCircleArc) {
  const Drawing d = import_via_file("circle.ngc", "G21\nG0 X5 Y0\nG3 X5 Y0 I-5 J0\n");
  ASSERT_EQ(d.curves.size(), 1u);
  const Extents e = d.extents();
  EXPECT_NEAR(e.min.x(), -5.0, 1e-6);
  EXPECT_NEAR(e.max.y(), 5.0, 1e-6);
}

TEST(GcodeImport, InchesAreConverted) {
  const Drawing d = import_via_file("inch.ngc", "G20\nG0 X0 Y0\nG1 X1 Y0\n");
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_NEAR(end_point(d.curves[0].spline()).x(), 25.4, 1e-12);
}

TEST(GcodeImport, ToolAboveTheWorkDoesNotCut) {
  const Drawing d = import_via_file("z.ngc", "G21\nG0 Z1\nG1 X10\nG1 Z-0.1\nG1 X20\n");
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_LT((start_point(d.curves[0].spline()) - Point2(10, 0)).norm(), 1e-12);
}

TEST(GcodeImport, LaserOffDoesNotCutWhenTheProgramSwitchesIt) {
  const Drawing d = import_via_file("laser.ngc", "G21\nM5\nG1 X10\nM3 S100\nG1 X20\nM5\nG1 X30\n");
  ASSERT_EQ(d.curves.size(), 1u);
  EXPECT_LT((start_point(d.curves[0].spline()) - Point2(10, 0)).norm(), 1e-12);
  EXPECT_LT((end_point(d.curves[0].spline()) - Point2(20, 0)).norm(), 1e-12);
}

// The spindle scan: M3/M4 with leading zeros switch it; a comment or another word's digits
// do not (then every feed move cuts, as in a program without spindle words).
TEST(GcodeImport, OnlyARealM3OrM4MeansTheProgramSwitchesTheSpindle) {
  const std::string moves = "G1 X10\nM5\nG1 X20\n";
  EXPECT_EQ(import_gcode_text("G21\nM003 S1\n" + moves, "a.ngc").curves.size(), 1u);
  EXPECT_EQ(import_gcode_text("G21\nm4\n" + moves, "b.ngc").curves.size(), 1u);
  for (const char* not_on : {"(M3)", ";M4", "G4 P3", "(MSG, M4 next)"}) {
    SCOPED_TRACE(not_on);
    EXPECT_EQ(
        import_gcode_text(std::string("G21\n") + not_on + "\n" + moves, "c.ngc").curves.size(), 2u);
  }
}

TEST(GcodeImport, InMemoryAndFileReadsAgree) {
  const std::string program = "G21\nG0 X5 Y0\nG3 X5 Y0 I-5 J0\nG1 X9 Y9\n";
  const Drawing a = import_gcode_text(program, "mem.ngc");
  const Drawing b = import_via_file("mem.ngc", program);
  ASSERT_EQ(a.curves.size(), b.curves.size());
  EXPECT_EQ(a.curves[0].spline().control.size(), b.curves[0].spline().control.size());
  EXPECT_EQ(a.curves[0].spline().knots, b.curves[0].spline().knots);
}

// M48 (enable feed and speed overrides) in a program: G-code, not an Excellon drill file.
TEST(GcodeImport, AnM48LineDoesNotMakeTheProgramADrillFile) {
  const Drawing d = import_via_file("m48.txt", "G21\nM48\nG0 X0 Y0\nG1 X10 Y0 F100\nM2\n");
  EXPECT_EQ(d.format, "G-code");
  EXPECT_EQ(d.curves.size(), 1u);
}

// PCB files are not drawings: the message says which commands plan them.
TEST(GcodeImport, PcbFilesAreSentToTheBoardCommands) {
  for (const auto& [name, text] :
       {std::pair<const char*, const char*>{"copper.gbr", "%FSLAX46Y46*%\n%MOMM*%\nM02*\n"},
        {"holes.txt", "M48\nMETRIC\n%\nM30\n"}}) {
    try {
      import_via_file(name, text);
      ADD_FAILURE() << name << " read as a drawing";
    } catch (const ImportError& e) {
      EXPECT_NE(std::string(e.what()).find("`engraver board`, `run`, `send` and `points` plan"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(GcodeImport, ArcEndOffTheCircleIsRefusedWithTheLine) {
  try {
    import_via_file("badarc.ngc", "G21\nG0 X10 Y0\nG2 X0 Y-12 I-10 J0\n");
    FAIL();
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("badarc.ngc: line 3: arc end is not on the circle"),
              std::string::npos)
        << e.what();
  }
}

// Binary data named .ngc (a copy of /bin/ls): "line 1: unexpected '\x7F'" said nothing of
// what the file is.
TEST(GcodeImport, BinaryDataIsNotAGcodeFile) {
  const std::string elf(
      "\x7F"
      "ELF\x02\x01\x01\0\0\0\nmore",
      15);
  try {
    import_via_file("elf.ngc", elf);
    FAIL();
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "elf.ngc: line 1: not a G-code file: binary data (a NUL byte at byte 7)"),
              std::string::npos)
        << e.what();
  }
  try {
    import_via_file("nul.ngc", "G21\nG0 X1" + std::string(1, '\0') + "\nM30\n");
    FAIL();
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "nul.ngc: line 2: not a G-code file: binary data (a NUL byte at byte 9)"),
              std::string::npos)
        << e.what();
  }
  // NUL padding after the program's end is not read.
  EXPECT_NO_THROW(
      import_via_file("padded.ngc", "G21\nG1 X1 Y1 F100\nM30\n" + std::string(16, '\0') + "\n"));
}

TEST(GcodeImport, OtherPlaneIsRefused) {
  try {
    import_via_file("g18.ngc", "G18\nG1 X1\n");
    FAIL();
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("line 1: G18"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace host

namespace host {
namespace {

TEST(GcodeImport, HugeOrNonNumericWordsAreRefusedWithTheLine) {
  for (const char* bad : {"G1 X1e300\n", "G1 Xnan\n", "G1 X\n", "G1e400 X1\n"}) {
    try {
      import_via_file("huge.ngc", std::string("G21\n") + bad);
      FAIL() << bad;
    } catch (const ImportError& e) {
      EXPECT_NE(std::string(e.what()).find("huge.ngc: line 2"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace host
