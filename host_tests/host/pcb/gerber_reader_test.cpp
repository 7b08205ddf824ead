// The Gerber reader on the project's own files, one per feature: areas and covered points
// computed by hand from the files (comments give the arithmetic).
#include <gtest/gtest.h>

#include <unistd.h>  // getpid

#include <algorithm>   // std::max, std::min
#include <cmath>       // M_PI, std::hypot
#include <filesystem>  // std::filesystem
#include <fstream>     // std::ofstream
#include <tuple>       // std::make_tuple

#include "host/lib/pcb/gerber_macro.h"
#include "host/lib/pcb/gerber_reader.h"
#include "host_tests/host/pcb/test_data.h"

namespace host::pcb {
namespace {

using test::area_mm2;
using test::data_file;

const double kPi = 3.14159265358979323846;

ClipperLib::cInt nm(double mm) {
  return static_cast<ClipperLib::cInt>(std::llround(mm * 1e6));
}

// Copper at a point (non-zero winding of the result's outers and holes).
bool covered(const PcbLayer& l, double x_mm, double y_mm) {
  int w = 0;
  for (const auto& p : l.polygons_nm) {
    if (ClipperLib::PointInPolygon({nm(x_mm), nm(y_mm)}, p) != 0) {
      w += ClipperLib::Orientation(p) ? 1 : -1;
    }
  }
  return w > 0;
}

// Copper area inside a box, mm².
double area_in(const PcbLayer& l, double x0, double y0, double x1, double y1) {
  ClipperLib::Clipper c;
  c.AddPaths(l.polygons_nm, ClipperLib::ptSubject, true);
  c.AddPath({{nm(x0), nm(y0)}, {nm(x1), nm(y0)}, {nm(x1), nm(y1)}, {nm(x0), nm(y1)}},
            ClipperLib::ptClip, true);
  ClipperLib::Paths out;
  c.Execute(ClipperLib::ctIntersection, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return area_mm2(out);
}

bool has_note(const PcbLayer& l, const std::string& part) {
  for (const std::string& n : l.notes) {
    if (n.find(part) != std::string::npos) return true;
  }
  return false;
}

// Inscribed polygons with 0.5 um chords: areas a little under the true ones.
const double kAreaTol = 0.005;  // mm²

TEST(GerberReader, MultiQuadrantArcsG75) {
  const PcbLayer l = read_gerber_file(data_file("arcs_multi_quadrant.gbr"));
  EXPECT_EQ(l.units, "mm");
  // Full circle r 3 stroked 0.5 wide: pi (3.25² - 2.75²) = 3 pi.
  EXPECT_NEAR(area_in(l, 0, 0, 10, 10), 3 * kPi, kAreaTol);
  EXPECT_FALSE(covered(l, 5, 5));
  EXPECT_TRUE(covered(l, 5, 2));
  EXPECT_TRUE(covered(l, 8, 5));
  // G03 from (12,5) to (18,5) around (15,5) goes under the centre; G02 from (12,8) to (18,8)
  // around (15,8) goes over it. Each: half of 3 pi plus two half caps (pi 0.25²).
  EXPECT_TRUE(covered(l, 15, 2));
  EXPECT_FALSE(covered(l, 15, 8 - 3));
  EXPECT_TRUE(covered(l, 15, 11));
  EXPECT_NEAR(area_in(l, 11, 0, 19, 6), 1.5 * kPi + kPi * 0.0625, kAreaTol);
  EXPECT_NEAR(area_in(l, 11, 6, 19, 12), 1.5 * kPi + kPi * 0.0625, kAreaTol);
  // Region: 6 x 6 square and a half disc of r 3 bulging right.
  EXPECT_NEAR(area_in(l, 19.5, 0, 30, 12), 36 + kPi * 9 / 2, kAreaTol);
  EXPECT_TRUE(covered(l, 28.9, 5));
}

TEST(GerberReader, SingleQuadrantArcsG74) {
  const PcbLayer l = read_gerber_file(data_file("arcs_single_quadrant.gbr"));
  // CW (2,5) -> (5,8) around (5,5): its middle at 135 degrees.
  EXPECT_TRUE(covered(l, 5 - 3 * std::cos(kPi / 4), 5 + 3 * std::sin(kPi / 4)));
  EXPECT_FALSE(covered(l, 5, 5));
  // CCW (2,2) -> (4,4) around (2,4): its middle at -45 degrees.
  EXPECT_TRUE(covered(l, 2 + 2 * std::cos(kPi / 4), 4 - 2 * std::sin(kPi / 4)));
  // Region: 6 x 6 square with one corner rounded at r 2: 36 - 4 + pi.
  EXPECT_NEAR(area_in(l, 9, 1, 17, 9), 32 + kPi, kAreaTol);
  EXPECT_TRUE(has_note(l, "G74"));
}

TEST(GerberReader, MacroPrimitivesVariablesAndExposure) {
  const PcbLayer l = read_gerber_file(data_file("macros.gbr"));
  // CIRC,2.0: circle d 2 minus circle d 1.
  EXPECT_NEAR(area_in(l, 3, 3, 7, 7), kPi * (1 - 0.25), kAreaTol);
  EXPECT_FALSE(covered(l, 5, 5));
  // OUTL: a 2 x 2 square turned 45 degrees.
  EXPECT_NEAR(area_in(l, 8, 3, 12, 7), 4.0, 1e-5);  // vertices rounded to 1 nm
  EXPECT_TRUE(covered(l, 10, 6.35));                // corner now on the y axis at sqrt(2)
  // POLY: hexagon in a circle of d 2: 3 sqrt(3) / 2.
  EXPECT_NEAR(area_in(l, 13, 3, 17, 7), 3 * std::sqrt(3.0) / 2, 1e-5);
  // THERM: ring d 3 / d 2 less four 0.5 gaps (integrated: 0.25177 mm² each).
  EXPECT_NEAR(area_in(l, 18, 3, 22, 7), kPi * (2.25 - 1) - 4 * 0.2517715, kAreaTol);
  EXPECT_FALSE(covered(l, 20 + 1.25 * std::cos(kPi / 4), 5 + 1.25 * std::sin(kPi / 4)));
  EXPECT_TRUE(covered(l, 21.25, 5));
  // LINES,1.0X0.3: $3 = 1x2+0.5 = 2.5; a 4 x 0.3 vector line, and a 2.5 x 0.4 centre line
  // at (0,1) turned 90 degrees about the origin (so at (-1,0), upright); overlap 0.4 x 0.3.
  EXPECT_NEAR(area_in(l, 22.5, 3, 28, 7), 1.2 + 1.0 - 0.12, 1e-5);
  EXPECT_TRUE(covered(l, 24, 6.2));
  // MIXED,0.5: 3 x 3 square less a circle of d $1x1.5x2 = 1.5 and a diamond of d 1.
  EXPECT_NEAR(area_in(l, 29, 3, 33, 7), 9 - kPi * 0.75 * 0.75 - 0.5, kAreaTol);
}

TEST(GerberMacroExpression, PrecedenceParenthesesVariables) {
  const std::vector<double> v{0, 0.5, 3};
  EXPECT_DOUBLE_EQ(evaluate_macro_expression("(1+$1)/2-0.25", v), 0.5);
  EXPECT_DOUBLE_EQ(evaluate_macro_expression("1+2x3", v), 7);
  EXPECT_DOUBLE_EQ(evaluate_macro_expression("2X(3+4)", v), 14);
  EXPECT_DOUBLE_EQ(evaluate_macro_expression("10/4/2", v), 1.25);
  EXPECT_DOUBLE_EQ(evaluate_macro_expression("-$2x-2", v), 6);
  EXPECT_DOUBLE_EQ(evaluate_macro_expression("$9", v), 0);  // unset
  EXPECT_DOUBLE_EQ(evaluate_macro_expression(".5+1.", v), 1.5);
  EXPECT_THROW(evaluate_macro_expression("1+", v), std::invalid_argument);
  EXPECT_THROW(evaluate_macro_expression("(1", v), std::invalid_argument);
  EXPECT_THROW(evaluate_macro_expression("1/0", v), std::invalid_argument);
  EXPECT_THROW(evaluate_macro_expression("1;2", v), std::invalid_argument);
}

TEST(GerberReader, ClearPolarity) {
  const PcbLayer l = read_gerber_file(data_file("polarity_clear.gbr"));
  // 10 x 10 less a 2 x 2 pad and a 6 mm track of d 1 (6 + pi/4), plus a dark pad of d 1
  // back inside the track.
  EXPECT_NEAR(area_mm2(l.polygons_nm), 100 - 4 - (6 + kPi / 4) + kPi / 4, kAreaTol);
  EXPECT_FALSE(covered(l, 5, 5));
  EXPECT_FALSE(covered(l, 3, 2));
  EXPECT_TRUE(covered(l, 5, 2));
  EXPECT_TRUE(covered(l, 1, 1));
}

// A D code defined twice after it drew: the note said "redefined" and the uses before took the
// first definition, the uses after the second, while gerbv (and pcb2gcode) draws every use
// with the last one (gerbv -x png of this file: both D10 flashes 4 mm wide). Read as gerbv
// reads it, and the note says which definition is used.
TEST(GerberReader, ARedefinedApertureIsItsLastDefinitionForEveryUseAsInGerbv) {
  const PcbLayer l = read_gerber_file(data_file("aperture_redefined.gbr"));
  // D10: the flash before the second definition is 4 mm wide too (1 mm before).
  EXPECT_NEAR(area_in(l, -1, -1, 5, 5), kPi * 4, kAreaTol);
  EXPECT_NEAR(area_in(l, 7, -1, 13, 5), kPi * 4, kAreaTol);
  // D11: the 1 mm square flashed and stroked from x 2 to 6 before its redefinition.
  EXPECT_NEAR(area_in(l, 0, 6, 8, 10), 5.0, kAreaTol);
  EXPECT_FALSE(covered(l, 3.2, 8.8));  // inside the earlier 3 x 2 mm rectangle only
  EXPECT_NEAR(area_in(l, 9, 7, 11, 9), 1.0, kAreaTol);
  EXPECT_TRUE(has_note(l,
                       "line 5: aperture D10 defined again at line 13 after it drew: every "
                       "use takes that last definition, those before it too, as gerbv draws "
                       "them"));
  EXPECT_TRUE(has_note(l, "line 6: aperture D11 defined again at line 14 after it drew"));
  EXPECT_TRUE(has_note(l,
                       "line 20: aperture D12 defined again, the same as before: nothing "
                       "changes"));
}

// A D code redefined by a block aperture: the flashes before the block are read with the
// last %AD (both 2 mm, as gerbv draws them; gerbv ignores %AB), those after are the block's.
TEST(GerberReader, AnApertureRedefinedByABlockIsTheBlockFromThere) {
  const PcbLayer l = read_gerber_file(data_file("aperture_redefined_block.gbr"));
  EXPECT_NEAR(area_in(l, 0, 0, 4, 4), kPi, kAreaTol);
  EXPECT_NEAR(area_in(l, 4, 0, 8, 4), kPi, kAreaTol);
  EXPECT_NEAR(area_in(l, 8, 0, 12, 4), kPi * 0.0625, kAreaTol);  // the block: a 0.5 mm pad
  EXPECT_TRUE(has_note(l, "line 4: aperture D10 defined again at line 8"));
  EXPECT_TRUE(has_note(l,
                       "line 14: aperture D10 redefined by a block aperture: the block from "
                       "here on"));
}

// Defined again before anything drew with it: the later definition, and the note says so.
TEST(GerberReader, AnApertureRedefinedBeforeItDrewIsItsLaterDefinition) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,1.0*%\nD10*\n%ADD10C,2.0*%\nX0Y0D03*\nM02*\n", "later.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), kPi, kAreaTol);
  EXPECT_TRUE(has_note(l,
                       "line 5: aperture D10 redefined before anything was drawn with it: "
                       "this later definition is used, as gerbv uses it"));
}

TEST(GerberReader, StepAndRepeat) {
  const PcbLayer l = read_gerber_file(data_file("step_repeat.gbr"));
  // Each copy: a 1 x 2 pad less a cleared circle of d 0.6, and a 0.8 mm track of d 1.
  const double copy = 2 - kPi * 0.09 + 0.8 + kPi * 0.25;
  EXPECT_NEAR(area_mm2(l.polygons_nm), 6 * copy, kAreaTol);
  for (int ix = 0; ix < 3; ++ix) {
    for (int iy = 0; iy < 2; ++iy) {
      EXPECT_FALSE(covered(l, 1 + 5 * ix, 1 + 4 * iy)) << ix << "," << iy;  // cleared
      EXPECT_TRUE(covered(l, 1 + 5 * ix, 1.8 + 4 * iy)) << ix << "," << iy;
      EXPECT_TRUE(covered(l, 3 + 5 * ix, 1 + 4 * iy)) << ix << "," << iy;
    }
  }
  EXPECT_FALSE(covered(l, 16, 1));  // no fourth column
}

TEST(GerberReader, StandardAperturesWithHoles) {
  const PcbLayer l = read_gerber_file(data_file("apertures.gbr"));
  EXPECT_EQ(l.apertures_or_tools, 7);
  EXPECT_NEAR(area_in(l, 1, 1, 5, 5), kPi * (1 - 0.25), kAreaTol);            // C 2 hole 1
  EXPECT_NEAR(area_in(l, 6, 1, 10, 5), 6 - kPi * 0.25, kAreaTol);             // R 3x2 hole 1
  EXPECT_NEAR(area_in(l, 11, 1, 15, 5), 1.5 * 1.5 + kPi * 0.5625, kAreaTol);  // O 3x1.5
  EXPECT_NEAR(area_in(l, 16.5, 1, 19.5, 5), 1 + kPi * 0.25 - kPi * 0.0625, kAreaTol);
  EXPECT_NEAR(area_in(l, 1, 6, 5, 10), 2.5 * std::sin(2 * kPi / 5), 1e-5);  // pentagon
  EXPECT_NEAR(area_in(l, 6, 6, 10, 10), 2 * std::sqrt(2.0) - kPi * 0.09, kAreaTol);
  // A 0.5 square drawn along (4,2): 0.25 + 0.5 (4 + 2).
  EXPECT_NEAR(area_in(l, 11, 7, 17, 11), 3.25, 1e-5);
  EXPECT_TRUE(has_note(l, "rectangular aperture"));
  EXPECT_FALSE(covered(l, 18, 3));  // the obround's hole
}

TEST(GerberReader, DeprecatedFormsAreReadWithNotes) {
  const PcbLayer l = read_gerber_file(data_file("deprecated_inch.gbr"));
  EXPECT_EQ(l.units, "inch");
  for (const char* n : {"trailing-zero", "%IPPOS", "%IN", "%LN", "%MI", "%SF", "%OF", "%AS", "G54",
                        "G70", "G90", "without an operation code", "single-quadrant", "M00"}) {
    EXPECT_TRUE(has_note(l, n)) << n;
  }
  const double in = 25.4;
  // Track (0.25,0.25)-(0.75,0.25) then, with no D code, up to (0.75,0.5).
  EXPECT_TRUE(covered(l, 0.5 * in, 0.25 * in));
  EXPECT_TRUE(covered(l, 0.75 * in, 0.4 * in));
  // "X01" with trailing zeros omitted is 01.0000 in: the 0.1 x 0.08 in pad at (1, 0.5).
  EXPECT_TRUE(covered(l, 1.049 * in, 0.539 * in));
  EXPECT_FALSE(covered(l, 1.051 * in, 0.5 * in));
  // Arc (0.25,0.75) -> (0.5,1.0) around (0.5,0.75), clockwise through 135 degrees.
  EXPECT_TRUE(
      covered(l, (0.5 - 0.25 * std::cos(kPi / 4)) * in, (0.75 + 0.25 * std::sin(kPi / 4)) * in));
}

// The legacy image parameters as the specification says: input code and knockout-off are
// ignored with a warning; a mirror, a quarter-turn rotation or a scale changes the image and
// is applied. A 1 mm square pad flashed at (10, 5) mm:
PcbLayer legacy(const std::string& params) {
  return read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n" + params + "%ADD10R,1X1*%\nD10*\nX10000000Y5000000D03*\nM02*\n",
      "legacy-F.Cu.gbr");
}

TEST(GerberLegacyParameters, InputCodeAndKnockoutOffAreIgnoredWithAWarning) {
  const PcbLayer l = legacy("%ICAS*%\n%KO*%\n");
  EXPECT_TRUE(covered(l, 10, 5));
  EXPECT_TRUE(has_note(l, "warning: %ICAS (deprecated input code: ASCII) ignored"));
  EXPECT_TRUE(has_note(l, "warning: %KO"));
}

TEST(GerberLegacyParameters, MirrorRotationAndScaleAreApplied) {
  const PcbLayer mirrored = legacy("%MIA1B0*%\n");
  EXPECT_TRUE(covered(mirrored, -10, 5));
  EXPECT_FALSE(covered(mirrored, 10, 5));
  EXPECT_NEAR(area_mm2(mirrored.polygons_nm), 1.0, 1e-9);  // orientation kept: positive
  const PcbLayer rotated = legacy("%IR90*%\n");
  EXPECT_TRUE(covered(rotated, -5, 10));
  EXPECT_FALSE(covered(rotated, 10, 5));
  const PcbLayer scaled = legacy("%SFA2B1*%\n");
  EXPECT_TRUE(covered(scaled, 20.9, 5));  // the pad is scaled too: 2 x 1 mm
  EXPECT_FALSE(covered(scaled, 10, 5));
  EXPECT_NEAR(area_mm2(scaled.polygons_nm), 2.0, 1e-9);
  EXPECT_TRUE(has_note(scaled, "warning: %SFA2B1 (deprecated scale factor) applied"));
  // The identities stay notes, no warning.
  const PcbLayer identity = legacy("%IPPOS*%\n%IR0*%\n%MIA0B0*%\n%SFA1B1*%\n%OFA0B0*%\n");
  EXPECT_TRUE(covered(identity, 10, 5));
  for (const std::string& n : identity.notes) EXPECT_EQ(n.find("warning"), std::string::npos) << n;
}

// The rest of the deprecated parameters (issue 24): %IO (image offset, current units) and %RO
// (layer rotation, any angle) move the image and are applied, %KOC with a box clears it where
// it stands (each as gerbv draws it: gerbv_agreement_test).
TEST(GerberLegacyParameters, ImageOffsetLayerRotationAndKnockoutAreApplied) {
  const PcbLayer offset = legacy("%IOA-10B1*%\n");
  EXPECT_TRUE(covered(offset, 0, 6));
  EXPECT_FALSE(covered(offset, 10, 5));
  EXPECT_TRUE(has_note(offset, "warning: %IOA-10B1 (deprecated image offset) applied"));
  const PcbLayer turned = legacy("%RO30*%\n");  // (10, 5) turned 30 degrees about the origin
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  EXPECT_TRUE(covered(turned, 10 * c - 5 * s, 10 * s + 5 * c));
  EXPECT_FALSE(covered(turned, 10, 5));
  EXPECT_NEAR(area_mm2(turned.polygons_nm), 1.0, 1e-5);  // corners rounded to 1 nm
  // A 0.4 x 0.4 mm box cleared out of the pad's lower left corner, before a second pad.
  const PcbLayer knocked = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,1X1*%\nD10*\nX10000000Y5000000D03*\n"
      "%KOCX9.5Y4.5I0.4J0.4*%\nX20000000Y5000000D03*\nM02*\n",
      "ko-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(knocked.polygons_nm), 2.0 - 0.16, 1e-6);
  EXPECT_FALSE(covered(knocked, 9.7, 4.7));
  EXPECT_TRUE(has_note(knocked, "warning: %KOC box (deprecated knockout) applied"));
}

// %IJ (image justify) as gerbv reads it (it was ignored, gerbv's test-image-justify-1 and -2
// not matching its picture): the 1 mm pad at (10, 5), box x 9.5..10.5, y 4.5..5.5, moved by
// -min on an L axis, by half the box (gerbv's centre) on a C axis, plus an axis's offset.
TEST(GerberLegacyParameters, ImageJustifyMovesTheImageAsGerbvDoes) {
  const PcbLayer lower_centre = legacy("%IJALBC*%\n");  // by (-9.5, 0.5): x 0..1, y 5..6
  EXPECT_TRUE(covered(lower_centre, 0.1, 5.9));
  EXPECT_FALSE(covered(lower_centre, 0.1, 4.9));
  EXPECT_FALSE(covered(lower_centre, 10, 5));
  EXPECT_TRUE(has_note(lower_centre,
                       "line 3: warning: %IJALBC (deprecated image justify) applied as gerbv "
                       "does: the image moved by -9.500, 0.500 mm"))
      << ::testing::PrintToString(lower_centre.notes);
  const PcbLayer offset = legacy("%IJB.5*%\n");  // A lower left, B 0.5 mm: by (-9.5, -4)
  EXPECT_TRUE(covered(offset, 0.1, 0.6));
  EXPECT_FALSE(covered(offset, 0.1, 0.4));
  EXPECT_FALSE(covered(offset, 10, 5));
  EXPECT_THROW(legacy("%IJX1*%\n"), PcbReadError);
}

// %IF (include file) as gerbv reads it (refused before: "unknown extended command"; gerbv's
// test-include-file-1.gbx): the named file's blocks in place, from the including file's
// folder; its line ends left out, so the including file's line numbers stay true.
TEST(GerberLegacyParameters, AnIncludeFileIsReadInPlaceFromTheFilesFolder) {
  const std::string dir = testing::TempDir() + "/include-" + std::to_string(::getpid());
  std::filesystem::create_directories(dir + "/parts");
  std::ofstream(dir + "/parts/cross.gbx") << "X-1000000Y0D02*\nD10*\nX1000000Y0D01*\n";
  std::ofstream(dir + "/main-F.Cu.gbr")
      << "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,0.2*%\n%IFparts/cross.gbx*%\nX0Y-1000000D02*\n"
         "X0Y1000000D01*\nM02*\n";
  const PcbLayer l = read_gerber_file(dir + "/main-F.Cu.gbr");
  EXPECT_TRUE(covered(l, -0.9, 0));  // the included stroke
  EXPECT_TRUE(covered(l, 0, 0.9));   // the file's own, after it
  // Two 2 x 0.2 mm strokes with round ends crossing in a 0.2 mm square.
  EXPECT_NEAR(area_mm2(l.polygons_nm), 2 * (2 * 0.2 + kPi * 0.01) - 0.04, 0.001);
  // A missing include names the %IF line; text in memory (an upload) cannot include.
  std::ofstream(dir + "/missing.gbr") << "%FSLAX46Y46*%\n%MOMM*%\n\n%IFnone.gbx*%\nM02*\n";
  try {
    read_gerber_file(dir + "/missing.gbr");
    ADD_FAILURE() << "a missing include read";
  } catch (const PcbReadError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.gbr:4: include file %IFnone.gbx: "),
              std::string::npos)
        << e.what();
  }
  // A file including itself: refused at the depth limit, its %IF line said twice, not nine times.
  std::ofstream(dir + "/self.gbr") << "%FSLAX46Y46*%\n%MOMM*%\n\n%IFself.gbr*%\nM02*\n";
  try {
    read_gerber_file(dir + "/self.gbr");
    ADD_FAILURE() << "a file including itself read";
  } catch (const PcbReadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("includes nested more than 8 deep"), std::string::npos) << what;
    size_t times = 0;
    for (size_t at = what.find("%IFself.gbr"); at != std::string::npos;
         at = what.find("%IFself.gbr", at + 1))
      ++times;
    EXPECT_EQ(times, 2u) << what;
  }
  EXPECT_THROW(read_gerber_file(dir + "/up.gbr"), PcbReadError);
  std::ofstream(dir + "/up.gbr") << "%FSLAX46Y46*%\n%MOMM*%\n%IF../x.gbx*%\nM02*\n";
  EXPECT_THROW(read_gerber_file(dir + "/up.gbr"), PcbReadError);
  EXPECT_THROW(
      read_gerber_text("%FSLAX46Y46*%\n%MOMM*%\n%IFparts/cross.gbx*%\nM02*\n", dir + "/upload.gbr"),
      PcbReadError);
  std::filesystem::remove_all(dir);
}

// %IPNEG: what is drawn is clear, copper the rest of the image's extent (its bounding box, as
// gerbv fills its picture): two 1 mm pads 10 mm apart make a 1 x 11 mm box less 2 mm².
TEST(GerberLegacyParameters, ANegativeImageIsItsBoxLessWhatIsDrawn) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%IPNEG*%\n%ADD10R,1X1*%\nD10*\nX0Y0D03*\nX10000000Y0D03*\n"
      "M02*\n",
      "neg-F.Cu.gbr");
  // gerbv's picture has a border of 5 % of the width and the height: 12.1 x 1.1 mm.
  EXPECT_NEAR(area_mm2(l.polygons_nm), 12.1 * 1.1 - 2.0, 1e-6);
  EXPECT_TRUE(covered(l, 5, 0));
  EXPECT_FALSE(covered(l, 0, 0));
  EXPECT_TRUE(has_note(l, "warning: %IPNEG (deprecated negative image) applied"));
}

// A round pad alone in a negative image: its bounding box less the pad left four slivers of
// copper in the corners, each an island to isolate. With gerbv's border, one ring.
TEST(GerberLegacyParameters, ANegativeImageOfOnePadIsOneRingNotSlivers) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%IPNEG*%\n%ADD10C,1*%\nD10*\nX0Y0D03*\nM02*\n", "neg1-F.Cu.gbr");
  int outers = 0;
  for (const auto& p : l.polygons_nm) outers += ClipperLib::Orientation(p) ? 1 : 0;
  EXPECT_EQ(outers, 1);
  EXPECT_NEAR(area_mm2(l.polygons_nm), 1.1 * 1.1 - kPi / 4, 1e-3);
  EXPECT_TRUE(covered(l, 0.52, 0));  // beyond the pad's edge, inside the border
}

// A dark knockout box (%KOD) is copper where it stands, as gerbv draws it (it was refused), and
// axis select AYBX swaps x and y (it was refused): both from the corpus of real files.
TEST(GerberLegacyParameters, ADarkKnockoutIsCopperAndAxisSelectSwapsXAndY) {
  const PcbLayer dark = legacy("%KODX0Y0I2J1*%\n");
  EXPECT_NEAR(area_mm2(dark.polygons_nm), 1.0 + 2.0, 1e-6);
  EXPECT_TRUE(covered(dark, 1.9, 0.9));
  EXPECT_TRUE(has_note(dark, "warning: %KOD box (deprecated knockout, dark) applied"));
  const PcbLayer swapped = legacy("%ASAYBX*%\n");
  EXPECT_TRUE(covered(swapped, 5, 10));
  EXPECT_FALSE(covered(swapped, 10, 5));
  EXPECT_NEAR(area_mm2(swapped.polygons_nm), 1.0, 1e-9);  // orientation kept: positive
  EXPECT_TRUE(has_note(swapped, "warning: %ASAYBX (deprecated axis select) applied"));
}

// A knockout without a box (it was refused by name): the objects up to the next %KO get their
// box, grown by the border K, cleared (C) before them, as gerbv draws it. A 1 mm pad in a
// 10 mm one: the box 3 x 3 mm around it is cleared, the pad itself drawn.
TEST(GerberLegacyParameters, AKnockoutWithoutABoxClearsAroundTheObjectsThatFollow) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,10X10*%\n%ADD11C,1*%\nD10*\nX5000000Y5000000D03*\n"
      "%KOCK1*%\nD11*\nX5000000Y5000000D03*\n%KO*%\nX9000000Y9000000D03*\nM02*\n",
      "kok-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), 100 - 9 + kPi / 4, 2e-3);  // the last pad lies inside
  EXPECT_TRUE(covered(l, 5, 5));
  EXPECT_FALSE(covered(l, 4.2, 5));
  EXPECT_FALSE(covered(l, 3.6, 6.4));
  EXPECT_TRUE(covered(l, 3.4, 5));
  EXPECT_TRUE(has_note(l,
                       "line 7: warning: %KOC around the objects that follow (deprecated "
                       "knockout) applied"));
}

// One image polarity per file, the last given (gerbv keeps the last): %IPPOS after %IPNEG was
// ignored, and the image read negative.
TEST(GerberLegacyParameters, TheLastImagePolarityApplies) {
  const PcbLayer l = legacy("%IPNEG*%\n%IPPOS*%\n");
  EXPECT_TRUE(covered(l, 10, 5));
  EXPECT_NEAR(area_mm2(l.polygons_nm), 1.0, 1e-9);
  EXPECT_FALSE(has_note(l, "%IPNEG (deprecated negative image) applied"));
  EXPECT_TRUE(has_note(l, "warning: %IPNEG replaced by the later %IPPOS (only the last applies)"));
  const PcbLayer neg = legacy("%IPPOS*%\n%IPNEG*%\n");
  EXPECT_FALSE(covered(neg, 10, 5));
}

// A repeated %IPNEG replaces the earlier one like any repeated parameter, and says so.
TEST(GerberLegacyParameters, ARepeatedNegativeImageSaysItReplacesTheEarlier) {
  const PcbLayer l = legacy("%IPNEG*%\n%IPNEG*%\n");
  EXPECT_FALSE(covered(l, 10, 5));
  EXPECT_TRUE(has_note(l,
                       "line 4: warning: %IPNEG replaced by the later %IPNEG (only the last "
                       "applies)"))
      << ::testing::PrintToString(l.notes);
  EXPECT_TRUE(has_note(l, "line 4: warning: %IPNEG (deprecated negative image) applied"));
}

// Each image parameter acts on the whole image, only its last value counts: a later %IR0
// undoes %IR90, so the %RO90 between them is the one transform in force (it was refused at
// %RO90 as two transforms together).
TEST(GerberLegacyParameters, ALaterIdentityUndoesAnEarlierTransformBeforeTheyCombine) {
  const PcbLayer l = legacy("%IR90*%\n%RO90*%\n%IR0*%\n");
  EXPECT_TRUE(covered(l, -5, 10));  // (10, 5) turned 90 degrees by %RO90 alone
  EXPECT_FALSE(covered(l, 10, 5));
  EXPECT_TRUE(has_note(l, "line 4: warning: %RO90 (deprecated layer rotation) applied"))
      << ::testing::PrintToString(l.notes);
  EXPECT_FALSE(has_note(l, "%IR90 (deprecated image rotation) applied"));
  // Nothing drawn under two transforms: nothing to refuse.
  EXPECT_NO_THROW(
      read_gerber_text("%FSLAX46Y46*%\n%MOMM*%\n%IR90*%\n%RO90*%\nM02*\n", "empty-F.Cu.gbr"));
}

// %KOC (or %KOD) with neither a box nor a border knocks out nothing (gerbv draws the file as
// without it): ignored with a warning; it was read as a knockout with border 0, which cleared
// a 1 mm box around the pad.
TEST(GerberLegacyParameters, AKnockoutWithoutParametersIsIgnored) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,10X10*%\n%ADD11C,1*%\nD10*\nX5000000Y5000000D03*\n"
      "%KOC*%\nD11*\nX5000000Y5000000D03*\n%KO*%\nM02*\n",
      "ko0-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), 100, 1e-6);
  EXPECT_TRUE(covered(l, 5.45, 5.45));
  EXPECT_TRUE(has_note(l,
                       "line 7: warning: %KOC without a box or a border (deprecated knockout) "
                       "ignored"))
      << ::testing::PrintToString(l.notes);
}

// Of a parameter given twice only the last applies; both were reported as applied.
TEST(GerberLegacyParameters, OfTwoRotationsOnlyTheLastIsReportedApplied) {
  const PcbLayer l = legacy("%RO30*%\n%RO90*%\n");
  EXPECT_TRUE(covered(l, -5, 10));  // (10, 5) turned 90 degrees
  EXPECT_TRUE(has_note(l, "line 4: warning: %RO90 (deprecated layer rotation) applied"));
  EXPECT_FALSE(has_note(l, "%RO30 (deprecated layer rotation) applied"))
      << ::testing::PrintToString(l.notes);
  EXPECT_TRUE(has_note(l, "warning: %RO30 replaced by the later %RO90 (only the last applies)"));
  // A later identity leaves nothing applied.
  const PcbLayer back = legacy("%RO30*%\n%RO0*%\n");
  EXPECT_TRUE(covered(back, 10, 5));
  for (const std::string& n : back.notes) EXPECT_EQ(n.find("applied"), std::string::npos) << n;
}

// "R,0.035": one size where the specification wants X and Y (EKF's files). gerbv draws a
// rectangle of no height (nothing); read as the square, more copper rather than less, with a
// warning. A definition whose numbers cannot be read ("R,0.03260.326") is left out with a
// warning when nothing uses it (refused where it is used: gerber_errors_test).
TEST(GerberReader, AOneSizeRectangleIsASquareAndAnUnusedBadApertureIsLeftOut) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,1*%\n%ADD11R,0.03260.326*%\nD10*\nX0Y0D03*\nM02*\n",
      "r1-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), 1.0, 1e-9);
  EXPECT_TRUE(covered(l, 0.45, 0.45));
  EXPECT_TRUE(has_note(l,
                       "line 3: warning: aperture D10 R has one size, not X and Y: read as a "
                       "square of that size (gerbv draws nothing)"));
  EXPECT_TRUE(has_note(l,
                       "warning: aperture D11 never used: its definition is left out (line 4: "
                       "bad aperture parameter '0.03260.326')"));
}

// A polygon aperture's rotation may be negative (clockwise; gerbv's own test file): it was
// refused as "a negative size". A hexagon turned -30 degrees has a vertex on the y axis.
TEST(GerberReader, APolygonsNegativeRotationIsClockwise) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10P,2X6X-30*%\nD10*\nX0Y0D03*\nM02*\n", "p-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), 1.5 * std::sqrt(3.0), 1e-5);  // hexagon of radius 1
  EXPECT_TRUE(covered(l, 0, -0.99));
  EXPECT_FALSE(covered(l, 0.99, 0));
}

// In an inch file a macro's rotation (45 deg) is an angle, not 45 in = 1.14 m: it was
// refused as "larger than 1 m". A 0.05 x 0.02 in centre line turned by 45 deg.
TEST(GerberReader, AnInchMacrosRotationIsNotALength) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX24Y24*%\n%MOIN*%\n%AMROT*\n21,1,$1,$2,0,0,$3*%\n%ADD10ROT,0.05X0.02X45*%\n"
      "D10*\nX10000Y10000D03*\nM02*\n",
      "rot-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), 0.05 * 0.02 * 25.4 * 25.4, 1e-6);
  EXPECT_TRUE(covered(l, 25.4 + 0.4, 25.4 + 0.4));   // along the 45 degree diagonal
  EXPECT_FALSE(covered(l, 25.4 + 0.5, 25.4 - 0.1));  // off it
}

// Coordinates with no D code before any operation (gerbv's exposure/example.grb starts
// "G01X00000Y00000*"): undefined by the spec; gerbv's aperture starts off, so they only move
// (they were refused). The next coordinates-only block repeats that D02: no track is drawn.
TEST(GerberReader, CoordinatesBeforeAnyOperationAreAMove) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX23Y23*%\n%MOIN*%\n%ADD10C,0.050*%\nG54D10*\nG01X0Y0*\nX1000Y0*\n"
      "X2000Y1000D03*\nM02*\n",
      "nod-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(l.polygons_nm), kPi * 0.635 * 0.635, 0.01);  // the flash alone
  EXPECT_TRUE(covered(l, 2 * 25.4, 25.4));
  EXPECT_FALSE(covered(l, 0.5 * 25.4, 0));
  EXPECT_TRUE(has_note(l,
                       "line 5: warning: coordinates without D01/D02/D03 before any operation: "
                       "read as a move (D02), as gerbv reads them"))
      << ::testing::PrintToString(l.notes);
}

// Arcs drawn with a rectangle or obround (not allowed by the spec; gerbv's
// test-aperture-rectangle-1.gbx and -obround-1.gbx, refused before): drawn as gerbv draws
// them, a stroke as wide as the aperture's X size (2 mm), square ends for a rectangle, round
// for an obround. A half circle of radius 10 mm from (10, 0) counter-clockwise to (-10, 0).
PcbLayer arc_with(const std::string& aperture) {
  return read_gerber_text("%FSLAX46Y46*%\n%MOMM*%\n%ADD10" + aperture +
                              "*%\nD10*\nG75*\nX10000000Y0D02*\n"
                              "G03X-10000000Y0I-10000000J0D01*\nM02*\n",
                          "arc-F.Cu.gbr");
}

TEST(GerberReader, AnArcWithARectangleOrObroundIsDrawnAsGerbvDrawsIt) {
  const PcbLayer rect = arc_with("R,2X1");
  EXPECT_TRUE(covered(rect, 0, 10.9));  // 1 mm either side of the circle at the top
  EXPECT_FALSE(covered(rect, 0, 11.1));
  EXPECT_TRUE(covered(rect, 10.9, -0.9));  // the square end below the start
  EXPECT_FALSE(covered(rect, 10.9, -1.1));
  EXPECT_NEAR(area_mm2(rect.polygons_nm), kPi * (11 * 11 - 9 * 9) / 2 + 2 * 2, 0.01);
  EXPECT_TRUE(has_note(rect,
                       "line 7: warning: an arc drawn with a rectangular aperture D10 (not "
                       "allowed by the spec): drawn as gerbv draws it, a stroke as wide as its "
                       "X size with square ends"))
      << ::testing::PrintToString(rect.notes);
  const PcbLayer obround = arc_with("O,2X1");
  EXPECT_TRUE(covered(obround, 0, 10.9));
  EXPECT_TRUE(covered(obround, 10, -0.9));  // the round end
  EXPECT_FALSE(covered(obround, 10.9, -0.9));
  EXPECT_NEAR(area_mm2(obround.polygons_nm), kPi * (11 * 11 - 9 * 9) / 2 + kPi, 0.01);
  EXPECT_TRUE(has_note(obround, "an arc drawn with an obround aperture D10"));
}

// How far a half-annulus arc stroke of radius r_mm and width w_mm with square ends (the half
// circle of arc_with: from (r, 0) counter-clockwise to (-r, 0)) lies from point (x, y): 0
// inside. The square ends are w/2 long below the x axis, as cairo's square caps put them.
double outside_square_ended_arc_mm(double r_mm, double w_mm, double x, double y) {
  const double h = w_mm / 2;
  const auto box = [](double x, double y, double x0, double y0, double x1, double y1) {
    const double dx = std::max({x0 - x, 0.0, x - x1}), dy = std::max({y0 - y, 0.0, y - y1});
    return std::hypot(dx, dy);
  };
  const double d_ends =
      std::min(box(x, y, r_mm - h, -h, r_mm + h, 0), box(x, y, -r_mm - h, -h, -r_mm + h, 0));
  if (y < 0) return d_ends;
  const double r = std::hypot(x, y);
  return std::min(d_ends, std::max({0.0, r - (r_mm + h), (r_mm - h) - r}));
}

// An arc with a rectangle ends in a square as wide as the stroke, at right angles to the
// arc's own end tangent, as cairo's square cap in gerbv; it was square to the last chord,
// turned by half the chord's angle: its outer corner stuck out up to w/2 x that angle
// (10 um at r 10 mm, w 2 mm; 5 um on a small arc), copper gerbv does not draw.
TEST(GerberReader, AnArcWithARectangleEndsSquareToItsTangent) {
  for (const auto& [r_mm, ap, w_mm] :
       {std::make_tuple(10.0, "R,2X1", 2.0), std::make_tuple(0.5, "R,0.25X0.25", 0.25),
        std::make_tuple(2.0, "R,0.6X0.2", 0.6)}) {
    const std::string r = std::to_string(static_cast<long>(r_mm * 1e6));
    // The same half circle counter-clockwise from (r, 0) and clockwise from (-r, 0).
    for (const std::string& arc : {"X" + r + "Y0D02*\nG03X-" + r + "Y0I-" + r + "J0D01*\n",
                                   "X-" + r + "Y0D02*\nG02X" + r + "Y0I" + r + "J0D01*\n"}) {
      const PcbLayer l = read_gerber_text(
          "%FSLAX46Y46*%\n%MOMM*%\n%ADD10" + std::string(ap) + "*%\nD10*\nG75*\n" + arc + "M02*\n",
          "arc-F.Cu.gbr");
      double worst_mm = 0;
      for (const auto& p : l.polygons_nm)
        for (const auto& v : p)
          worst_mm =
              std::max(worst_mm, outside_square_ended_arc_mm(r_mm, w_mm, v.X * 1e-6, v.Y * 1e-6));
      EXPECT_LT(worst_mm, 0.0005) << arc << ap;  // the 0.5 um chord tolerance
      // Nothing less than the exact stroke: its corners and edges, 1 um inside.
      const double h = w_mm / 2 - 0.001;
      for (const auto& [x, y] : {std::make_pair(r_mm + h, -h), std::make_pair(r_mm - h, -h),
                                 std::make_pair(-r_mm + h, -h), std::make_pair(-r_mm - h, -h),
                                 std::make_pair(0.0, r_mm + h), std::make_pair(0.0, r_mm - h)})
        EXPECT_TRUE(covered(l, x, y)) << arc << ap << " at (" << x << ", " << y << ")";
    }
  }
}

// A line drawn with an obround: gerbv strokes it as a circle of the obround's X size; copper
// where either that or the obround swept along the line puts it. Along X from (0, 0) to
// (10, 0): a 2 x 1 mm obround is 2 mm wide in gerbv's reading, a 1 x 2 mm one in ours.
TEST(GerberReader, ALineWithAnObroundIsCopperInBothReadings) {
  for (const char* ap : {"O,2X1", "O,1X2"}) {
    const PcbLayer l = read_gerber_text(std::string("%FSLAX46Y46*%\n%MOMM*%\n%ADD10") + ap +
                                            "*%\nD10*\nX0Y0D02*\nX10000000Y0D01*\nM02*\n",
                                        "line-F.Cu.gbr");
    EXPECT_TRUE(covered(l, 5, 0.9)) << ap;
    EXPECT_FALSE(covered(l, 5, 1.1)) << ap;
    EXPECT_TRUE(has_note(l, "a draw with an obround aperture")) << ap;
  }
}

// Aperture parameters gerbv reads and the spec does not define (both refused before): an
// empty last parameter (gerbv's exposure/example.grb "%ADD14C,0.1X*%") and a polygon's sixth
// (test-aperture-polygon-flash-1.gbx), each ignored with a warning.
TEST(GerberReader, AnEmptyLastParameterAndAPolygonsSixthAreIgnored) {
  const PcbLayer c = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD14C,2X*%\nD14*\nX0Y0D03*\nM02*\n", "c-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(c.polygons_nm), kPi, 0.01);  // a 2 mm circle as a polygon
  EXPECT_TRUE(has_note(c,
                       "line 3: warning: aperture D14: an empty last parameter ignored, as "
                       "gerbv does"))
      << ::testing::PrintToString(c.notes);
  const PcbLayer p = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD12P,2X4X0X0.5X0.5X0.3*%\nD12*\nX0Y0D03*\nM02*\n", "p-F.Cu.gbr");
  EXPECT_NEAR(area_mm2(p.polygons_nm), 2 - 0.25, 1e-5);  // a square of diagonal 2, its hole
  EXPECT_FALSE(covered(p, 0, 0));
  EXPECT_TRUE(has_note(p, "warning: polygon aperture D12: a sixth parameter ignored"));
}

// A size after an aperture definition's '*' in its '%' block (gerbv's polarity/6_vbat.gbr
// "%ADD181C,.031*X.015%", refused before): ignored with a warning, as gerbv ignores it; the
// aperture is the circle alone. Anything else there is still refused.
TEST(GerberReader, ASizeAfterAnApertureDefinitionsStarIsIgnored) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD181C,2*X1%\nD181*\nX0Y0D03*\nM02*\n", "a-F.Cu.gbr");
  EXPECT_TRUE(covered(l, 0, 0));
  EXPECT_NEAR(area_mm2(l.polygons_nm), kPi, 0.01);
  EXPECT_TRUE(has_note(l, "line 3: warning: 'X1' after the aperture definition's '*' ignored"))
      << ::testing::PrintToString(l.notes);
  EXPECT_THROW(read_gerber_text("%FSLAX46Y46*%\n%MOMM*%\n%LPC*X1%\nM02*\n", "b-F.Cu.gbr"),
               PcbReadError);
}

// No %MO: the format's legacy default, inch (gerbv and pcb2gcode read it so), with a warning.
TEST(GerberReader, NoUnitsMeansInchWithAWarning) {
  const PcbLayer l = read_gerber_text("%FSLAX24Y24*%\n%ADD10C,0.1*%\nD10*\nX10000Y5000D03*\nM02*\n",
                                      "no-mo-F.Cu.gbr");
  EXPECT_EQ(l.units, "inch");
  EXPECT_TRUE(covered(l, 25.4, 12.7));
  EXPECT_NEAR(area_mm2(l.polygons_nm), kPi * 1.27 * 1.27, 0.01);
  EXPECT_TRUE(has_note(l, "warning: no units (%MO) before aperture D10: inch assumed"));
}

// A G03 whose I/J puts the centre on its own end point: a zero-radius arc, drawn as the
// straight line between its ends (it was refused: "0.000 mm at the end").
TEST(GerberReader, AZeroRadiusArcIsAStraightLine) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,0.2*%\nD10*\nG75*\nX0Y0D02*\n"
      "G03X1000000Y0I1000000J0D01*\nM02*\n",
      "arc-F.Cu.gbr");
  EXPECT_TRUE(covered(l, 0.5, 0));
  EXPECT_FALSE(covered(l, 0.5, 0.2));
  EXPECT_NEAR(area_mm2(l.polygons_nm), 1 * 0.2 + kPi * 0.01, 1e-3);
  EXPECT_TRUE(has_note(l, "zero radius"));
}

// Arcs whose ends are 50.8 um off their start radius (3-decimal inch I/J, as Protel writes):
// copper is where our reading (through both end points) or gerbv's (the start radius up to
// the end angle) puts it. Both points below are copper only in gerbv's reading.
TEST(GerberReader, IllDefinedArcsAreCopperInBothReadings) {
  const PcbLayer l = read_gerber_file(data_file("ill_defined_arcs.gbr"));
  // The stroke (0.254 mm wide) ends at radius 12.7508 mm round (12.7, 0); gerbv's end cap is
  // at radius 12.7, so radius 12.6 just above the axis is inside gerbv's stroke only.
  EXPECT_TRUE(covered(l, 12.7 + 12.6, 0.005));
  EXPECT_TRUE(covered(l, 12.7 + 12.75, 0.005));  // and ours
  // The region's arc (centre (63.5, 0)) ends at radius 12.6492; gerbv keeps 12.7.
  const double a = 175 * kPi / 180;
  EXPECT_TRUE(covered(l, 63.5 + 12.68 * std::cos(a), 12.68 * std::sin(a)));
  EXPECT_FALSE(covered(l, 63.5 + 12.75 * std::cos(a), 12.75 * std::sin(a)));
  EXPECT_TRUE(has_note(l,
                       "warning: 2 arcs whose end is not on their circle (start and end radii "
                       "differ by up to 50.8 um)"));
}

// A clear ill-defined arc clears only what both readings clear: copper stays wherever
// either reading leaves it.
TEST(GerberReader, AClearIllDefinedArcClearsOnlyWhatBothReadingsClear) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX23Y23*%\n%MOIN*%\n%ADD10C,0.010*%\n%ADD11R,1.2X0.2*%\nD11*\nX1000Y0D03*\n"
      "%LPC*%\nD10*\nG75*\nX0Y0D02*\nG02X1002Y0I500J0D01*\nM02*\n",
      "clear-F.Cu.gbr");
  EXPECT_TRUE(covered(l, 12.7 + 12.6, 0.005));   // cleared by gerbv's reading only
  EXPECT_FALSE(covered(l, 12.7 + 12.7, 0.005));  // cleared by both
  EXPECT_TRUE(covered(l, 12.7 + 12.85, 0.005));  // cleared by ours only
}

// A block aperture (%AB, in the specification since 2016): the objects drawn inside, with
// their polarities, flashed like an aperture at each flash point. Here a 2 mm square with a
// 0.5 mm clear hole, flashed at (10, 0) and (20, 0).
TEST(GerberReader, BlockAperturesAreFlashedWithTheirPolarities) {
  const PcbLayer l = read_gerber_text(
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10R,2X2*%\n%ADD11C,0.5*%\n%ABD12*%\nD10*\nX0Y0D03*\n"
      "%LPC*%\nD11*\nX0Y0D03*\n%AB*%\n%LPD*%\nD12*\nX10000000Y0D03*\nX20000000Y0D03*\nM02*\n",
      "block-F.Cu.gbr");
  EXPECT_TRUE(covered(l, 10.8, 0));
  EXPECT_TRUE(covered(l, 20.8, 0.8));
  EXPECT_FALSE(covered(l, 10, 0));  // the clear hole
  EXPECT_FALSE(covered(l, 0, 0));   // nothing where the block was defined
  EXPECT_NEAR(area_mm2(l.polygons_nm), 2 * (4 - kPi * 0.0625), 2e-3);  // flattened holes
}

TEST(GerberReader, RegionsWithCutInAndClockwiseContours) {
  const PcbLayer l = read_gerber_file(data_file("regions.gbr"));
  EXPECT_NEAR(area_mm2(l.polygons_nm), 100 - 16 + 9, 1e-9);
  EXPECT_FALSE(covered(l, 5, 5));
  EXPECT_TRUE(covered(l, 13, 1));
  int holes = 0;
  for (const auto& p : l.polygons_nm) holes += !ClipperLib::Orientation(p);
  EXPECT_EQ(holes, 1);
}

TEST(GerberReader, LayerKindFromX2ElseNameElseCaller) {
  GerberOptions top;
  top.kind_if_unknown = LayerKind::kCopperTop;
  EXPECT_EQ(read_gerber_file(data_file("x2_attributes.gbr"), top).kind, LayerKind::kCopperBottom);
  EXPECT_EQ(read_gerber_file(data_file("regions.gbr")).kind, LayerKind::kUnknown);
  EXPECT_EQ(read_gerber_file(data_file("regions.gbr"), top).kind, LayerKind::kCopperTop);
  EXPECT_EQ(read_gerber_file(data_file("outline-Edge.Cuts.gbr")).kind, LayerKind::kOutline);
  const std::string text = "%FSLAX33Y33*%%MOMM*%%ADD10C,1*%D10*X0Y0D03*M02*";
  EXPECT_EQ(read_gerber_text(text, "board.GBL").kind, LayerKind::kCopperBottom);
  EXPECT_EQ(read_gerber_text(text, "board-F_Cu.gbr").kind, LayerKind::kCopperTop);
  EXPECT_EQ(read_gerber_text(text, "board.gm1").kind, LayerKind::kOutline);
}

TEST(GerberReader, OutlineStrokesJoinIntoOneClosedPath) {
  const PcbLayer l = read_gerber_file(data_file("outline-Edge.Cuts.gbr"));
  ASSERT_TRUE(l.outline_paths_are_open);
  ASSERT_EQ(l.polygons_nm.size(), 1u);
  const auto& p = l.polygons_nm[0];
  EXPECT_TRUE(p.front() == p.back());
  double length = 0;
  for (size_t k = 1; k < p.size(); ++k) {
    length += std::hypot(static_cast<double>(p[k].X - p[k - 1].X),
                         static_cast<double>(p[k].Y - p[k - 1].Y));
  }
  // 18 + 8 + 22 + 8 straight and two quarter circles of r 2 (pi each).
  EXPECT_NEAR(length * 1e-6, 56 + 2 * kPi, 0.001);
}

TEST(GerberReader, ArcToleranceIsTheChordError) {
  const std::string text = "%FSLAX33Y33*%%MOMM*%%ADD10C,10*%D10*X0Y0D03*M02*";
  for (double tol_nm : {100.0, 500.0, 10000.0}) {
    GerberOptions o;
    o.arc_tolerance_nm = tol_nm;
    const PcbLayer l = read_gerber_text(text, "t.gbr", o);
    ASSERT_EQ(l.polygons_nm.size(), 1u);
    const auto& p = l.polygons_nm[0];
    EXPECT_EQ(l.arc_tolerance_nm, tol_nm);
    for (size_t k = 0; k < p.size(); ++k) {
      const auto& a = p[k];
      const auto& b = p[(k + 1) % p.size()];
      EXPECT_NEAR(std::hypot(static_cast<double>(a.X), static_cast<double>(a.Y)), 5e6, 1);
      // Distance from the centre to the chord's middle: r - sagitta.
      const double mid = std::hypot((a.X + b.X) / 2.0, (a.Y + b.Y) / 2.0);
      EXPECT_LE(5e6 - mid, tol_nm + 1);
    }
  }
}

}  // namespace
}  // namespace host::pcb

namespace host::pcb {
namespace {

// Copies that overlap: a clear object of a later copy also clears the earlier copies.
TEST(GerberReader, OverlappingStepAndRepeatCopiesClearEachOther) {
  const std::string text =
      "%FSLAX33Y33*%\n%MOMM*%\n%ADD10R,2X2*%\n%ADD11C,0.6*%\n%SRX2Y1I1J0*%\nD10*\n"
      "X0Y0D03*\n%LPC*%\nD11*\nX0Y0D03*\n%LPD*%\n%SR*%\nM02*\n";
  const PcbLayer l = read_gerber_text(text, "sr.gbr");
  // Squares over x -1..2; copy 2's clear circle at x 1 also cuts copy 1, and copy 2's
  // square covers the right half of copy 1's circle at x 0.
  EXPECT_NEAR(area_mm2(l.polygons_nm), 6 - 0.09 * kPi - 0.045 * kPi, kAreaTol);
  EXPECT_FALSE(covered(l, 0.85, 0));
  EXPECT_FALSE(covered(l, -0.15, 0));
  EXPECT_TRUE(covered(l, 0.15, 0));
}

}  // namespace
}  // namespace host::pcb
