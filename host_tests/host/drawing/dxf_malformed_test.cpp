// Malformed DXF files: each is refused with an ImportError naming the file, the entity and
// what is wrong (never a crash, never a silently wrong drawing).
#include <gtest/gtest.h>

#include <fstream>

#include "host/lib/drawing/drawing.h"
#include "host_tests/host/drawing/dxf_builder.h"

namespace host {
namespace {

using test::dxf_text;
using test::Groups;
using test::spline_entity;
using test::write_temp;

// The message of the ImportError that importing `text` raises ("" when none).
std::string import_error(const std::string& name, const std::string& text) {
  try {
    import_drawing(write_temp(name, text));
  } catch (const ImportError& e) {
    return e.what();
  }
  return "";
}

const std::vector<std::pair<double, double>> kCtrl = {{0, 0}, {1, 2}, {3, 2}, {4, 0}};

#define EXPECT_HAS(msg, part) EXPECT_NE((msg).find(part), std::string::npos) << (msg)

TEST(DxfMalformed, TruncatedFileNamesTheFileAndTheEntity) {
  std::string text = dxf_text(spline_entity(3, {0, 0, 0, 0, 1, 1, 1, 1}, kCtrl));
  text.resize(text.find("40\n1\n"));  // cut in the middle of the knots
  const std::string m = import_error("truncated.dxf", text);
  EXPECT_HAS(m, "truncated.dxf");
  EXPECT_HAS(m, "SPLINE");
  EXPECT_HAS(m, "truncated");
}

TEST(DxfMalformed, FileEndingAfterAGroupCodeIsTruncated) {
  const std::string m = import_error("halfpair.dxf", "0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n");
  EXPECT_HAS(m, "halfpair.dxf: line 7, in LINE");
  EXPECT_HAS(m, "without its value");
}

TEST(DxfMalformed, BadGroupCodeNamesTheLine) {
  const std::string text = "0\nSECTION\n2\nENTITIES\n0\nLINE\n5\nAB\nten\n1.0\n0\nENDSEC\n0\nEOF\n";
  const std::string m = import_error("badcode.dxf", text);
  EXPECT_HAS(m, "badcode.dxf: line 9, in LINE starting at line 5 (handle AB)");
  EXPECT_HAS(m, "'ten' is not a DXF group code");
}

// Binary data named .dxf (a copy of /bin/ls): the first line, escaped, "is not a DXF group
// code" said nothing of what the file is.
TEST(DxfMalformed, BinaryDataIsNotADxfFile) {
  const std::string elf(
      "\x7F"
      "ELF\x02\x01\x01\0\0\0\nmore",
      15);
  const std::string path = write_temp("elf.dxf", elf);
  try {
    import_drawing(path);
    FAIL() << "imported";
  } catch (const ImportError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": line 1: not a DXF file: binary data (a NUL byte at byte 7)");
  }
  const std::string later = "0\nSECTION\n" + std::string(1, '\0') + "\n";
  EXPECT_HAS(import_error("nul.dxf", later),
             "nul.dxf: line 3: not a DXF file: binary data (a NUL byte at byte 10)");
  // No NUL, another control byte.
  EXPECT_HAS(import_error("ctl.dxf",
                          "0\nSECTION\nab\x03"
                          "cd\nmore\n"),
             "ctl.dxf: line 3: not a DXF file: binary data (byte 0x03 at byte 12)");
}

TEST(DxfMalformed, KnotCountNotMatchingTheAnnouncedCount) {
  Groups g;
  g.g(0, "SPLINE").g(5, "2B").g(8, "0").g(70, 8).g(71, 3).g(72, 8).g(73, 4);
  for (double k : {0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0}) g.g(40, k);  // 7 of 8
  for (const auto& p : kCtrl) g.pt(10, p.first, p.second);
  const std::string m = import_error("knotcount.dxf", dxf_text(g.str()));
  EXPECT_HAS(m, "knotcount.dxf: SPLINE #1 (handle 2B");
  EXPECT_HAS(m, "announces 8 knots (group 72) but lists 7");
}

TEST(DxfMalformed, KnotCountNotMatchingControlPointsAndDegree) {
  const std::string m =
      import_error("knotrule.dxf", dxf_text(spline_entity(3, {0, 0, 0, 1, 1, 1, 1}, kCtrl)));
  EXPECT_HAS(m, "SPLINE #1 (handle 2A");
  EXPECT_HAS(m, "7 knots for 4 control points of degree 3 (need 8)");
}

TEST(DxfMalformed, DecreasingKnots) {
  const std::string m =
      import_error("decreasing.dxf", dxf_text(spline_entity(3, {0, 0, 0, 0, 1, 1, 0.5, 1}, kCtrl)));
  EXPECT_HAS(m, "SPLINE #1 (handle 2A");
  EXPECT_HAS(m, "knots decrease at index 6");
}

TEST(DxfMalformed, ZeroWeight) {
  const std::string m = import_error(
      "zeroweight.dxf",
      dxf_text(spline_entity(3, {0, 0, 0, 0, 1, 1, 1, 1}, kCtrl, {1, 0, 1, 1}, 8 | 4)));
  EXPECT_HAS(m, "SPLINE #1 (handle 2A");
  EXPECT_HAS(m, "weight 1 is 0 (weights must be positive)");
}

TEST(DxfMalformed, WeightCountNotMatchingControlPoints) {
  const std::string m =
      import_error("weightcount.dxf",
                   dxf_text(spline_entity(3, {0, 0, 0, 0, 1, 1, 1, 1}, kCtrl, {1, 2}, 8 | 4)));
  EXPECT_HAS(m, "2 weights (group 41) for 4 control points");
}

TEST(DxfMalformed, NanCoordinate) {
  const std::string line = "0\nLINE\n5\n3C\n8\n0\n10\nnan\n20\n0\n11\n1\n21\n1\n";
  const std::string m = import_error("nan.dxf", dxf_text(line));
  EXPECT_HAS(m, "nan.dxf");
  EXPECT_HAS(m, "LINE starting at line");
  EXPECT_HAS(m, "(handle 3C)");
  EXPECT_HAS(m, "group 10 value 'nan' is not a finite number");
}

TEST(DxfMalformed, DegreeAboveThree) {
  const std::string m = import_error(
      "degree5.dxf", dxf_text(spline_entity(5, {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1},
                                            {{0, 0}, {1, 1}, {2, 0}, {3, 1}, {4, 0}, {5, 1}})));
  EXPECT_HAS(m, "degree 5 (group 71); the machine takes degree 1 to 3");
}

TEST(DxfMalformed, HugeAnnouncedCountIsRefusedBeforeAllocation) {
  Groups g;
  g.g(0, "SPLINE").g(5, "2C").g(8, "0").g(71, 3).g(72, 2000000000);
  const std::string m = import_error("huge.dxf", dxf_text(g.str()));
  EXPECT_HAS(m, "group 72 announces 2000000000 items");
}

TEST(DxfMalformed, NegativeArcRadius) {
  const std::string arc = Groups()
                              .g(0, "ARC")
                              .g(5, "3D")
                              .g(8, "0")
                              .pt(10, 0, 0)
                              .g(40, -1.0)
                              .g(50, 0.0)
                              .g(51, 90.0)
                              .str();
  const std::string m = import_error("negradius.dxf", dxf_text(arc));
  EXPECT_HAS(m, "ARC #1 (handle 3D");
  EXPECT_HAS(m, "radius is -1 (must be positive)");
}

TEST(DxfMalformed, TiltedExtrusionIsRefused) {
  const std::string c = Groups()
                            .g(0, "CIRCLE")
                            .g(5, "3E")
                            .g(8, "0")
                            .pt(10, 0, 0)
                            .g(40, 1.0)
                            .g(210, 0.6)
                            .g(220, 0.0)
                            .g(230, 0.8)
                            .str();
  const std::string m = import_error("tilted.dxf", dxf_text(c));
  EXPECT_HAS(m, "CIRCLE #1 (handle 3E");
  EXPECT_HAS(m, "tilted plane");
}

TEST(DxfMalformed, SelfReferencingBlockIsRefused) {
  Groups b;
  b.g(0, "BLOCK").g(8, "0").g(2, "LOOP").g(70, 0).pt(10, 0, 0).g(3, "LOOP");
  b.g(0, "INSERT").g(5, "50").g(8, "0").g(2, "LOOP").pt(10, 1, 0);
  b.g(0, "ENDBLK").g(8, "0");
  const std::string ins =
      Groups().g(0, "INSERT").g(5, "51").g(8, "0").g(2, "LOOP").pt(10, 0, 0).str();
  const std::string m = import_error("loop.dxf", dxf_text(ins, 4, b.str()));
  EXPECT_HAS(m, "nested deeper than 16");
}

TEST(DxfMalformed, BinaryDxfIsRefused) {
  const std::string m = import_error("binary.dxf", std::string("AutoCAD Binary DXF\r\n\x1a\0", 22));
  EXPECT_HAS(m, "binary DXF is not supported");
}

TEST(DxfMalformed, EmptyFileIsRefused) {
  EXPECT_HAS(import_error("empty.dxf", ""), "empty");
}

TEST(DxfMalformed, MissingFileIsRefused) {
  try {
    import_drawing("/nonexistent/drawing.dxf");
    FAIL();
  } catch (const ImportError& e) {
    EXPECT_HAS(std::string(e.what()), "/nonexistent/drawing.dxf: cannot open");
  }
}

}  // namespace
}  // namespace host

namespace host {
namespace {

TEST(DxfMalformed, LwpolylineBulgeBeforeTheFirstVertexIsRefused) {
  // dxflib would write this bulge before the start of its vertex array.
  const std::string p =
      "0\nLWPOLYLINE\n5\n4A\n8\n0\n90\n2\n70\n0\n42\n0.5\n10\n0\n20\n0\n10\n1\n20\n0\n";
  const std::string m = import_error("bulgefirst.dxf", dxf_text(p));
  EXPECT_HAS(m, "in LWPOLYLINE starting at line");
  EXPECT_HAS(m, "(handle 4A)");
  EXPECT_HAS(m, "a bulge (group 42) before the first vertex");
}

TEST(DxfMalformed, LwpolylineVertexCountMismatchIsRefused) {
  const std::string p = "0\nLWPOLYLINE\n5\n4B\n8\n0\n90\n3\n70\n0\n10\n0\n20\n0\n10\n1\n20\n0\n";
  const std::string m = import_error("vertexcount.dxf", dxf_text(p));
  EXPECT_HAS(m, "(handle 4B): announces 3 vertices (group 90) but lists 2");
}

TEST(DxfMalformed, LwpolylineWithoutVertexCountIsRefused) {
  const std::string p = "0\nLWPOLYLINE\n5\n4C\n8\n0\n70\n0\n10\n0\n20\n0\n10\n1\n20\n0\n";
  EXPECT_HAS(import_error("nocount.dxf", dxf_text(p)),
             "vertex data before the vertex count (group 90)");
}

// Every line of the bundled sample replaced in turn by something wrong (a different
// number, garbage, nothing) or the file cut there: the import either succeeds or throws
// ImportError. Never a crash, never another exception.
TEST(DxfMalformed, MutatedSampleNeverCrashes) {
  std::ifstream in(std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_GT(lines.size(), 1000u);
  const char* replacements[] = {"-1", "0", "2000000", "1e308", "x", "", "42", "nan"};
  int imported = 0, refused = 0;
  // Every 13th line (coprime with the 6-line control point and 2-line knot records, so each
  // group code and each value takes its turn): about 190 lines, 9 mutations each.
  for (size_t i = 0; i < lines.size(); i += 13) {
    for (int r = 0; r < 9; ++r) {
      std::vector<std::string> m = lines;
      if (r == 8) {
        m.resize(i);  // truncated here
      } else {
        m[i] = replacements[r];
      }
      std::string text;
      for (const std::string& l : m) text += l + "\n";
      try {
        import_drawing(test::write_temp("mutated.dxf", text));
        ++imported;
      } catch (const ImportError&) {
        ++refused;
      }
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(imported, 0);
}

}  // namespace
}  // namespace host
