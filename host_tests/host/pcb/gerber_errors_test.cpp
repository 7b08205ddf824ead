// Bad Gerber and Excellon input is refused with the file, the line and what is wrong, and
// nothing is returned.
#include <gtest/gtest.h>

#include "host/lib/pcb/excellon_reader.h"
#include "host/lib/pcb/gerber_reader.h"

namespace host::pcb {
namespace {

std::string gerber_refusal(const std::string& text) {
  try {
    read_gerber_text(text, "bad.gbr");
  } catch (const PcbReadError& e) {
    return e.what();
  }
  return "(read without error)";
}

std::string excellon_refusal(const std::string& text) {
  try {
    read_excellon_text(text, "bad.drl");
  } catch (const PcbReadError& e) {
    return e.what();
  }
  return "(read without error)";
}

const char* kHead = "%FSLAX33Y33*%\n%MOMM*%\n%ADD10C,1*%\n";  // lines 1-3

struct Case {
  const char* body;      // after kHead (line 4 on)
  const char* expected;  // the whole message starts with this
};

TEST(GerberErrors, NameFileLineAndProblem) {
  const Case cases[] = {
      {"D10*\nX0Y0D03*\n", "bad.gbr:5: the file ends without M02"},
      {"D99*\nM02*\n", "bad.gbr:4: D99 selects an aperture that is not defined"},
      {"X0Y0D03*\nM02*\n", "bad.gbr:4: drawing or flashing before any aperture is selected"},
      {"D10*\nG36*\nX0Y0D02*\nX1000Y0D03*\nG37*\nM02*\n", "bad.gbr:7: flash (D03) inside a region"},
      {"G37*\nM02*\n", "bad.gbr:4: G37 without G36"},
      {"D10*\nG36*\nX0Y0D02*\nM02*\n", "bad.gbr:7: G36 region still open at M02"},
      {"G99*\nM02*\n", "bad.gbr:4: unknown or unsupported G code G99"},
      {"M05*\nM02*\n", "bad.gbr:4: unknown M code M05"},
      {"D10*\nX0Y0Q5D03*\nM02*\n", "bad.gbr:5: unexpected 'Q'"},
      {"D10*\nX0Y0D01D03*\nM02*\n", "bad.gbr:5: two operations"},
      {"D10*\nX12a4Y0D03*\nM02*\n", "bad.gbr:5: unexpected 'a'"},
      {"D10*\nX99999999999Y0D03*\nM02*\n", "bad.gbr:5: coordinate '99999999999' is beyond 10 m"},
      {"%ADD11P,1X4*%\nD11*\nG75*\nG02X1000Y0I500J0D01*\nM02*\n",
       "bad.gbr:7: an arc drawn with a non-circular aperture D11"},
      {"D10*\nG74*\nG02X10000Y0I1000J0D01*\nM02*\n",
       "bad.gbr:6: arc end point is not on its circle (radius 1.000 mm at the start, 11.000"},
      {"D10*\nG75*\nG02X10000Y0I1000J0D01*\nM02*\n",
       "bad.gbr:6: arc end point is not on its circle (radius 1.000 mm at the start, 9.000 mm"},
      // Radii 10 and 11.2 mm: more than the 1 mm an ill-defined arc may be off.
      {"D10*\nG75*\nX0Y0D02*\nG02X21200Y0I10000J0D01*\nM02*\n",
       "bad.gbr:7: arc end point is not on its circle (radius 10.000 mm at the start, 11.200 mm "
       "at the end; more than 1.000 mm apart"},
      // Radii 0.1 and 0.25 mm: more than 0.1 mm and more than half the start radius.
      {"D10*\nG75*\nX0Y0D02*\nG02X350Y0I100J0D01*\nM02*\n",
       "bad.gbr:7: arc end point is not on its circle (radius 0.100 mm at the start, 0.250 mm "
       "at the end; more than 0.100 mm apart"},
      // A definition with parameters that cannot be read is refused where it is used.
      {"%ADD11FOO,1*%\nD11*\nM02*\n",
       "bad.gbr:5: D11 selects an aperture whose definition was refused: line 4: aperture D11 "
       "uses 'FOO', which is neither"},
      {"%ADD11C*%\nM02*\n", "bad.gbr:4: aperture D11 C takes 1 to 3 parameters, got 0"},
      {"%ADD11C,-1*%\nD11*\nM02*\n",
       "bad.gbr:5: D11 selects an aperture whose definition was refused: line 4: aperture D11 "
       "has a negative size"},
      {"%ADD11P,1X2*%\nD11*\nM02*\n",
       "bad.gbr:5: D11 selects an aperture whose definition was refused: line 4: polygon "
       "aperture D11 needs 3 to 12 vertices"},
      {"%ADD11C,2000*%\nD11*\nM02*\n",
       "bad.gbr:5: D11 selects an aperture whose definition was refused: line 4: aperture D11 "
       "is larger than 1 m"},
      {"%ADD11R,0.03260.326*%\nD10*\nX0Y0D03*\nD11*\nM02*\n",
       "bad.gbr:7: D11 selects an aperture whose definition was refused: line 4: bad aperture "
       "parameter '0.03260.326'"},
      {"%AMM1*\n1,1,$1x,0,0*%\n%ADD11M1,1*%\nD11*\nM02*\n",
       "bad.gbr:7: D11 selects an aperture whose definition was refused: line 6: macro M1: "
       "missing number"},
      {"%AMM1*\n9,1,1,0,0*%\n%ADD11M1*%\nM02*\n", "bad.gbr:6: macro M1: unknown primitive '9'"},
      {"%AMM1*\n1,1,1*%\n%ADD11M1*%\nM02*\n",
       "bad.gbr:6: macro M1: circle (1) needs 4 modifiers, got 2"},
      {"%AMM1*\n4,1,3,0,0,1,0*%\n%ADD11M1*%\nM02*\n",
       "bad.gbr:6: macro M1: outline (4) needs 11 modifiers, got 6"},
      {"%AMM1*\n1,7777777777777777777,1,0,0*%\n%ADD11M1*%\nM02*\n",
       "bad.gbr:6: macro M1: exposure must be 0 or 1, not 7777777777777777777"},
      {"%SRX1000Y1000I1J1*%\nM02*\n", "bad.gbr:4: step-and-repeat '%SRX1000Y1000I1J1' makes more"},
      {"%SRX0Y1I1J1*%\nM02*\n", "bad.gbr:4: step-and-repeat '%SRX0Y1I1J1' needs whole"},
      {"%IPX*%\nM02*\n", "bad.gbr:4: image polarity 'X' is neither POS nor NEG"},
      {"%RO400*%\nM02*\n", "bad.gbr:4: layer rotation %RO400 must be -360 .. 360 degrees"},
      {"%OFA1B0*%\n%IOA0B1*%\nD10*\nX0Y0D03*\nM02*\n",
       "bad.gbr:5: the deprecated image transforms %OFA1B0 and %IOA0B1 together are not"},
      {"%MIA2*%\nM02*\n", "bad.gbr:4: mirror image '%MIA2': A and B take 0 or 1"},
      {"%SFA0B1*%\nM02*\n", "bad.gbr:4: scale factor %SFA0B1 must be above 0"},
      {"%IR45*%\nM02*\n", "bad.gbr:4: image rotation %IR45 must be 0, 90, 180 or 270"},
      {"%MIA1*%\n%IR90*%\nD10*\nX0Y0D03*\nM02*\n",
       "bad.gbr:5: the deprecated image transforms %MIA1 and %IR90 together are not supported"},
      {"%IOX1Y2*%\nM02*\n", "bad.gbr:4: bad image offset 'X1Y2': expected A<a>B<b>"},
      {"%IOA1A2*%\nM02*\n", "bad.gbr:4: bad image offset 'A1A2': expected A<a>B<b>"},
      {"%OFX1*%\nM02*\n", "bad.gbr:4: bad offset 'X1': expected A<a>B<b>"},
      {"%IR90*%\n%RO90*%\n%IR180*%\nD10*\nX0Y0D03*\nM02*\n",
       "bad.gbr:6: the deprecated image transforms %RO90 and %IR180 together are not supported"},
      {"%ICEB*%\nM02*\n", "bad.gbr:4: input code %ICEB is not supported (only ASCII, %ICAS)"},
      {"%KOCX1Y1*%\nM02*\n",
       "bad.gbr:4: %KOCX1Y1 (deprecated knockout): a box needs all of X, Y, I and J"},
      {"%ASAXBX*%\nM02*\n", "bad.gbr:4: axis select %ASAXBX is neither AXBY nor AYBX"},
      {"%ABD12*%\nM02*\n", "bad.gbr:5: block aperture D12 still open at M02"},
      {"%AB*%\nM02*\n", "bad.gbr:4: %AB closes a block aperture that was never opened"},
      {"%ABD12*%\n%ADD10C,1*%\nD10*\nX0Y0D03*\n%AB*%\nD12*\nX1000Y0D01*\nM02*\n",
       "bad.gbr:10: block aperture D12 can only be flashed (D03)"},
      {"%LR45*%\nM02*\n", "bad.gbr:4: aperture transformation %LR45 is not supported"},
      {"%XY12*%\nM02*\n", "bad.gbr:4: unknown extended command '%XY12'"},
      {"%LPX*%\nM02*\n", "bad.gbr:4: polarity 'X' is neither D nor C"},
      {"%MOFT*%\nM02*\n", "bad.gbr:4: unit 'FT' is neither MM nor IN"},
      {"%FSLAX3Y3*%\nM02*\n", "bad.gbr:4: format '%FSLAX3Y3' needs X with two digits"},
      {"D10*\n%LPD*\nM02*\n", "bad.gbr:5: '%' block never closed"},
      {"D10*\nX0Y0D03\n", "bad.gbr:5: data block 'X0Y0D03' never ends with '*'"},
  };
  for (const Case& c : cases) {
    const std::string msg = gerber_refusal(std::string(kHead) + c.body);
    EXPECT_EQ(msg.rfind(c.expected, 0), 0u) << "input:\n" << c.body << "message: " << msg;
  }
}

TEST(GerberErrors, CoordinatesNeedFormatAndUnits) {
  EXPECT_EQ(gerber_refusal("%MOMM*%\n%ADD10C,1*%\nD10*\nX0Y0D03*\nM02*\n")
                .rfind("bad.gbr:4: coordinates before the format (%FS)", 0),
            0u);
}

TEST(GerberErrors, FilesThatCannotBeOpened) {
  EXPECT_THROW(read_gerber_file("/nonexistent/board.gbr"), PcbReadError);
  try {
    read_gerber_file("/nonexistent/board.gbr");
  } catch (const PcbReadError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/board.gbr: cannot open the file");
  }
  EXPECT_THROW(read_excellon_file("/nonexistent/board.drl"), PcbReadError);
  // A folder given as a layer file (issue 24's tester: "cannot open the file" only).
  const std::string dir = testing::TempDir();
  try {
    read_gerber_file(dir);
    ADD_FAILURE() << "a folder read as Gerber";
  } catch (const PcbReadError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a file");
  }
}

// Binary data read as Gerber (issue 24's tester: an ELF head gave "data block '\x7FELF..."
// cut at the first NUL, with no closing quote and no problem stated).
TEST(GerberErrors, BinaryDataIsNotAGerberFile) {
  const std::string elf(
      "\x7F"
      "ELF\x02\x01\x01\0\0\0\nmore",
      15);
  EXPECT_EQ(gerber_refusal(elf),
            "bad.gbr:1: not a Gerber file: binary data (a NUL byte at byte 7)");
  const std::string later =
      std::string(kHead) + "D10*\nX0Y0D03*\n" + std::string(1, '\0') + "M02*\n";
  EXPECT_EQ(gerber_refusal(later).rfind("bad.gbr:6: not a Gerber file: binary data", 0), 0u)
      << gerber_refusal(later);
  const std::string in_a_block =
      std::string(kHead) + "D10*\nX0Y0" + std::string(1, '\0') + "D03*\nM02*\n";
  EXPECT_EQ(gerber_refusal(in_a_block).rfind("bad.gbr:5: not a Gerber file: binary data", 0), 0u)
      << gerber_refusal(in_a_block);
  // NUL padding (and Ctrl-Z) after M02 is not read, as DXF, G-code and Excellon leave it (an
  // outside tester: only Gerber refused a padded file).
  const std::string padded =
      std::string(kHead) + "D10*\nX0Y0D03*\nM02*\n" + std::string(100, '\0') + "\x1a";
  EXPECT_EQ(gerber_refusal(padded), "(read without error)");
  EXPECT_EQ(read_gerber_text(padded, "ok.gbr").notes.size(), 0u);
}

// Binary data read as Excellon (a copy of /bin/ls as --drill x.drl): "unknown or unsupported
// command '\x7FELF..." cut at the first NUL, with no closing quote.
TEST(ExcellonErrors, BinaryDataIsNotAnExcellonFile) {
  const std::string elf(
      "\x7F"
      "ELF\x02\x01\x01\0\0\0\nmore",
      15);
  EXPECT_EQ(excellon_refusal(elf),
            "bad.drl:1: not an Excellon file: binary data (a NUL byte at byte 7)");
  const std::string later = "M48\nMETRIC\nT1C0.8\n%\n" + std::string(1, '\0') + "M30\n";
  EXPECT_EQ(excellon_refusal(later),
            "bad.drl:5: not an Excellon file: binary data (a NUL byte at byte 20)");
}

TEST(ExcellonErrors, NameFileLineAndProblem) {
  const Case cases[] = {
      {"M48\nMETRIC\nT1C0.8\nT2C1.0\n%\nX1.0Y1.0\nM30\n",
       "bad.drl:6: a hole or slot before any tool is selected (Tn), and the header defines 2 (T1, "
       "T2): which one is meant is not known"},
      {"M48\nMETRIC\n%\nX1.0Y1.0\nM30\n",
       "bad.drl:4: a hole or slot before any tool is selected (Tn), and no tool is defined"},
      {"M48\nMETRIC\nT1C0.8\n%\nT2\nM30\n", "bad.drl:5: tool T2 has no diameter"},
      {"M48\nT1C0.8\n%\nT1\nM30\n", "bad.drl:4: tool T1 defined before the units"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y1.0\n", "bad.drl:6: the file ends without M30"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nQ7\nM30\n", "bad.drl:6: unknown or unsupported command 'Q7'"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nG00X1.0Y1.0\nM15\nG02X2.0Y2.0\nM30\n",
       "bad.drl:8: routed arcs (G02) are not supported"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y1.0Z3\nM30\n", "bad.drl:6: unexpected 'Z'"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0.0Y1\nM30\n", "bad.drl:6: bad coordinate '1.0.0'"},
      {"M48\nMETRIC\nT1C0\n%\n", "bad.drl:3: tool T1 diameter 0 is not above 0"},
      {"M48\nMETRIC,QZ\n%\n", "bad.drl:2: unknown field 'QZ'"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nM15\nM30\n", "bad.drl:6: M15 (tool down) outside route mode"},
      {"T1C0.8\nX1Y1\nM30\n", "bad.drl:1: tool T1 defined before the units"},
      {"M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y1.0G85\nM30\n",
       "bad.drl:6: G85 slot without an end point"},
  };
  for (const Case& c : cases) {
    const std::string msg = excellon_refusal(c.body);
    EXPECT_EQ(msg.rfind(c.expected, 0), 0u) << "input:\n" << c.body << "message: " << msg;
  }
}

}  // namespace
}  // namespace host::pcb

namespace host::pcb {
namespace {

// A fuzzer's find: overlapping step-and-repeat copies with a clear object in each make every
// polarity change re-clip the whole grown copper (1.07 s in Release for 203 x 2 copies).
TEST(GerberErrors, OverlappingCopiesWithClearObjectsBeyondTheReclipLimitAreRefused) {
  const std::string text =
      "%FSLAX26Y26*%\n%MOMM*%\n%ADD10C,1*%\n%ADD11C,0.5*%\n%SRX203Y2I0.4J0.4*%\n%LPD*%\n"
      "D10*\nX0Y0D03*\n%LPC*%\nD11*\nX200000Y0D03*\n%SR*%\nM02*\n";
  GerberOptions o;
  o.max_reclipped_vertices = 1000000;
  try {
    read_gerber_text(text, "sr.gbr", o);
    FAIL() << "read without error";
  } catch (const PcbReadError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("sr.gbr:13: the polarity changes re-clip more than "
                                          "1000000 copper vertices",
                                          0),
              0u)
        << e.what();
  }
  // The same block with fewer copies reads: one area, two holes left by the last copies.
  std::string small = text;
  small.replace(small.find("X203Y2"), 6, "X20Y2");
  const PcbLayer l = read_gerber_text(small, "sr.gbr", o);
  EXPECT_EQ(l.polygons_nm.size(), 3u);
}

TEST(GerberErrors, StepAndRepeatBeyondTheVertexLimitIsRefused) {
  // 100 x 100 copies of a circle pad (about 3000 vertices at 0.5 um for d 5 mm).
  const std::string text =
      "%FSLAX33Y33*%\n%MOMM*%\n%ADD10C,5*%\n%SRX100Y100I6J6*%\nD10*\nX0Y0D03*\n%SR*%\nM02*\n";
  GerberOptions o;
  o.max_vertices = 1000000;
  try {
    read_gerber_text(text, "panel.gbr", o);
    FAIL() << "read without error";
  } catch (const PcbReadError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("panel.gbr:7: the copper needs more than 1000000 "
                                          "polygon vertices: too complex to read",
                                          0),
              0u)
        << e.what();
  }
  o.arc_tolerance_nm = 50000;  // coarse circles: the same panel fits
  EXPECT_EQ(read_gerber_text(text, "panel.gbr", o).polygons_nm.size(), 10000u);
}

}  // namespace
}  // namespace host::pcb

namespace host::pcb {
namespace {

// gerbv reads small arcs off by up to half their radius (its jj/l1-3.grb: 0.255 mm at the
// start, 0.136 mm at the end); so does the reader, with copper where either reading puts it.
TEST(GerberErrors, ASmallArcOffByLessThanHalfItsRadiusReads) {
  EXPECT_EQ(
      gerber_refusal(std::string(kHead) + "D10*\nG75*\nX0Y0D02*\nG02X391Y0I255J0D01*\nM02*\n"),
      "(read without error)");
  EXPECT_EQ(
      gerber_refusal(std::string(kHead) + "D10*\nG75*\nX0Y0D02*\nG02X20200Y0I10000J0D01*\nM02*\n"),
      "(read without error)");
}

}  // namespace
}  // namespace host::pcb
