// Board outlines as real files draw them, read from small Gerbers and planned as cut-outs:
// the loops come from the union of the strokes at their width, so duplicates, T-junctions
// and gaps narrower than the stroke close as gerbv shows them, and strokes that enclose
// nothing are left out with a warning.
#include <gtest/gtest.h>

#include <cmath>   // std::llround
#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/pcb/cutout.h"
#include "host/lib/pcb/gerber_reader.h"

namespace host::pcb {
namespace {

struct Stroke {
  std::vector<std::pair<double, double>> points_mm;
};

std::string coord(double mm) {
  return std::to_string(std::llround(mm * 1e6));
}

// An outline Gerber (mm, 6 decimals) drawing each stroke with a round aperture of `width_mm`.
std::string outline_gerber(const std::vector<Stroke>& strokes, double width_mm) {
  std::string g =
      "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C," + std::to_string(width_mm) + "*%\nD10*\nG01*\n";
  for (const Stroke& s : strokes) {
    for (size_t k = 0; k < s.points_mm.size(); ++k) {
      g += "X" + coord(s.points_mm[k].first) + "Y" + coord(s.points_mm[k].second) +
           (k == 0 ? "D02*\n" : "D01*\n");
    }
  }
  return g + "M02*\n";
}

CutoutPlan plan(const std::string& gerber) {
  const PcbLayer l = read_gerber_text(gerber, "board-Edge_Cuts.gbr");
  EXPECT_EQ(l.kind, LayerKind::kOutline);
  CutoutOptions o;
  o.cutter_diameter_mm = 1.0;
  o.tab_width_mm = 0;
  return plan_cutout(l, o);
}

bool has_note(const CutoutPlan& p, const std::string& part) {
  for (const std::string& n : p.notes) {
    if (n.find(part) != std::string::npos) return true;
  }
  return false;
}

// The 30 x 20 mm rectangle's four edges.
const Stroke kBottom{{{0, 0}, {30, 0}}}, kRight{{{30, 0}, {30, 20}}}, kTop{{{30, 20}, {0, 20}}},
    kLeft{{{0, 20}, {0, 0}}};

// TARGET 3001!: every edge drawn twice, the bottom edge also as two overlapping halves, and
// the right edge running on past the corners (T-junctions with the top and bottom edges).
TEST(OutlineStrokes, DuplicatesOverlapsAndTJunctionsMakeOneBoard) {
  const CutoutPlan p = plan(outline_gerber(
      {kBottom, kRight, kTop, kLeft, kLeft, kTop, kRight, kBottom, Stroke{{{0, 0}, {18, 0}}},
       Stroke{{{12, 0}, {30, 0}}}, Stroke{{{30, -3}, {30, 23}}}},
      0.1));
  EXPECT_NEAR(p.board_area_mm2, 600.0, 0.01);
  ASSERT_EQ(p.loops.size(), 1u);
  EXPECT_TRUE(p.loops[0].outer);
}

// EAGLE: a stray open stroke beside the rectangle encloses nothing: the board is cut, the
// stroke is named in a warning.
TEST(OutlineStrokes, AStrayOpenStrokeBesideTheBoardIsLeftOutWithAWarning) {
  const CutoutPlan p =
      plan(outline_gerber({kBottom, kRight, kTop, kLeft, Stroke{{{35, 5}, {35, 15}}}}, 0.1));
  EXPECT_NEAR(p.board_area_mm2, 600.0, 0.01);
  EXPECT_EQ(p.loops.size(), 1u);
  EXPECT_TRUE(has_note(p, "1 group(s) of outline strokes enclose nothing (first near (35"));
}

// pcb-rnd: slot strokes drawn inside the board enclose nothing: the board stays whole (no
// cut-out loop for them), with a warning.
TEST(OutlineStrokes, SlotStrokesInsideTheBoardAreLeftOutWithAWarning) {
  const CutoutPlan p = plan(outline_gerber(
      {kBottom, kRight, kTop, kLeft, Stroke{{{10, 10}, {20, 10}}}, Stroke{{{5, 5}, {5, 8}}}}, 0.1));
  EXPECT_NEAR(p.board_area_mm2, 600.0, 0.01);
  EXPECT_EQ(p.loops.size(), 1u);
  EXPECT_TRUE(has_note(p, "2 group(s) of outline strokes enclose nothing"));
}

// EAGLE milling layer: gaps of 0.025 to 0.19 mm between 0.2 mm strokes, which gerbv draws
// closed, close; the loop runs along the centre lines.
TEST(OutlineStrokes, GapsNarrowerThanTheStrokeWidthClose) {
  const CutoutPlan p =
      plan(outline_gerber({Stroke{{{0, 0}, {29.975, 0}}}, Stroke{{{30, 0.05}, {30, 20}}},
                           Stroke{{{29.81, 20}, {0, 20}}}, Stroke{{{0, 19.9}, {0, 0.1}}}},
                          0.2));
  EXPECT_NEAR(p.board_area_mm2, 600.0, 0.05);
  EXPECT_EQ(p.loops.size(), 1u);
}

// A gap wider than the stroke is open, as gerbv shows it: refused with the place.
TEST(OutlineStrokes, AGapWiderThanTheStrokeIsRefusedWithThePlace) {
  try {
    plan(outline_gerber({kBottom, kRight, kTop, Stroke{{{0, 20}, {0, 0.3}}}}, 0.2));
    FAIL() << "an outline with a 0.3 mm gap was accepted";
  } catch (const CutoutError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("does not close"), std::string::npos) << m;
    EXPECT_NE(m.find("within 0.202 mm"), std::string::npos) << m;
  }
}

// Two boards side by side sharing an edge (a panel): both are board, and a closed loop
// inside one is a cut-out.
TEST(OutlineStrokes, ASharedEdgeAndAnInnerLoop) {
  const CutoutPlan p = plan(outline_gerber(
      {Stroke{{{0, 0}, {60, 0}, {60, 20}, {0, 20}, {0, 0}}}, Stroke{{{30, 0}, {30, 20}}},
       Stroke{{{10, 5}, {20, 5}, {20, 15}, {10, 15}, {10, 5}}}},
      0.1));
  EXPECT_NEAR(p.board_area_mm2, 1200.0 - 100.0, 0.05);
}

}  // namespace
}  // namespace host::pcb
