// The Excellon reader on the project's own drill files: exact positions in nanometres for
// every number format (METRIC/INCH, LZ/TZ, decimal, KiCad's FORMAT comment), slots both ways.
#include <gtest/gtest.h>

#include "host/lib/pcb/excellon_reader.h"
#include "host_tests/host/pcb/test_data.h"

namespace host::pcb {
namespace {

using test::data_file;

void expect_hole(const Hole& h, ClipperLib::cInt x, ClipperLib::cInt y, ClipperLib::cInt d,
                 int tool) {
  EXPECT_EQ(h.at.x, x);
  EXPECT_EQ(h.at.y, y);
  EXPECT_EQ(h.diameter_nm, d);
  EXPECT_EQ(h.tool, tool);
}

TEST(ExcellonReader, MetricLeadingZerosKept) {
  const PcbLayer l = read_excellon_file(data_file("metric_lz.drl"));
  EXPECT_EQ(l.kind, LayerKind::kDrill);
  EXPECT_EQ(l.units, "mm");
  EXPECT_EQ(l.apertures_or_tools, 2);
  ASSERT_EQ(l.holes.size(), 3u);
  // METRIC,LZ,000.000: "+010000" is 010.000 mm.
  expect_hole(l.holes[0], 10000000, 5000000, 800000, 1);
  expect_hole(l.holes[1], 12540000, 5000000, 800000, 1);
  expect_hole(l.holes[2], 20000000, 10000000, 1000000, 2);
  EXPECT_TRUE(l.slots.empty());
}

TEST(ExcellonReader, InchTrailingZerosKept) {
  const PcbLayer l = read_excellon_file(data_file("inch_tz.drl"));
  EXPECT_EQ(l.units, "inch");
  ASSERT_EQ(l.holes.size(), 3u);
  // INCH,TZ with the default 2.4 digits: "3937" is 0.3937 in = 9.99998 mm.
  expect_hole(l.holes[0], 9999980, 5001260, 800100, 1);
  expect_hole(l.holes[1], 12539980, 5001260, 800100, 1);
  expect_hole(l.holes[2], 19999960, 9999980, 1016000, 2);
}

TEST(ExcellonReader, InchLeadingZerosFromFormatComment) {
  const PcbLayer l = read_excellon_file(data_file("inch_lz_format.drl"));
  ASSERT_EQ(l.holes.size(), 2u);
  // 2:4, trailing zeros suppressed: "01" is 01 in, "005" is 00.5 in, "0125" 01.25 in.
  expect_hole(l.holes[0], 25400000, 12700000, 635000, 3);
  expect_hole(l.holes[1], 31750000, 19050000, 635000, 3);
}

TEST(ExcellonReader, DecimalCoordinatesAndG85Slot) {
  const PcbLayer l = read_excellon_file(data_file("slots_decimal.drl"));
  ASSERT_EQ(l.holes.size(), 2u);
  expect_hole(l.holes[0], 10000000, -5000000, 800000, 1);
  expect_hole(l.holes[1], 12540000, -5000000, 800000, 1);
  ASSERT_EQ(l.slots.size(), 1u);
  EXPECT_EQ(l.slots[0].from.x, 20000000);
  EXPECT_EQ(l.slots[0].from.y, -10000000);
  EXPECT_EQ(l.slots[0].to.x, 24000000);
  EXPECT_EQ(l.slots[0].to.y, -10000000);
  EXPECT_EQ(l.slots[0].diameter_nm, 1200000);
  EXPECT_EQ(l.slots[0].tool, 2);
}

TEST(ExcellonReader, RoutedSlotsG00M15G01M16) {
  const PcbLayer l = read_excellon_file(data_file("routed_slot.drl"));
  ASSERT_EQ(l.slots.size(), 2u);
  EXPECT_EQ(l.slots[0].from.x, 20000000);
  EXPECT_EQ(l.slots[0].to.x, 24000000);
  EXPECT_EQ(l.slots[0].to.y, -14000000);
  EXPECT_EQ(l.slots[1].from.x, 24000000);
  EXPECT_EQ(l.slots[1].to.y, -16000000);
  ASSERT_EQ(l.holes.size(), 1u);  // back in drill mode (G05)
  expect_hole(l.holes[0], 30000000, -14000000, 1200000, 1);
}

TEST(ExcellonReader, IncrementalAndBodyToolsAndUnitsSwitch) {
  const std::string text =
      "M48\nMETRIC,TZ\n%\nT1C1.0\nG91\nX1.0Y1.0\nX1.0\nG90\nM72\nX1.0Y1.0\nM30\n";
  const PcbLayer l = read_excellon_text(text, "mem.drl");
  ASSERT_EQ(l.holes.size(), 3u);
  expect_hole(l.holes[0], 1000000, 1000000, 1000000, 1);
  expect_hole(l.holes[1], 2000000, 1000000, 1000000, 1);
  expect_hole(l.holes[2], 25400000, 25400000, 1000000, 1);
  EXPECT_FALSE(l.notes.empty());
}

// ---- Excellon as its writers write it ----

bool has_note(const PcbLayer& l, const std::string& part) {
  for (const std::string& n : l.notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}

TEST(ExcellonWriters, UnitsAndZerosOnTheM71Line) {  // Upverter
  const PcbLayer l = read_excellon_text("M48\nM71,TZ\nT1C0.8\n%\nT1\nX10000Y5000\nM30\n", "u.drl");
  EXPECT_EQ(l.units, "mm");
  ASSERT_EQ(l.holes.size(), 1u);
  expect_hole(l.holes[0], 10000000, 5000000, 800000, 1);  // TZ, 3.3: "10000" is 10.000
}

// EKF's drill files define a T0 and select it: a tool like any (T0 unloads the tool only when
// no T0 is defined). A hole before any tool is selected takes the only tool defined, with a
// warning (with several it is refused: gerber_errors_test).
TEST(ExcellonWriters, ADefinedToolZeroAndAHoleBeforeTheOnlyTool) {
  const PcbLayer t0 = read_excellon_text(
      "M48\nMETRIC\nT0C0.5\nT1C0.8\n%\nT0\nX1.0Y1.0\nT1\nX2.0Y1.0\nM30\n", "t0.drl");
  ASSERT_EQ(t0.holes.size(), 2u);
  expect_hole(t0.holes[0], 1000000, 1000000, 500000, 0);
  const PcbLayer first = read_excellon_text("M48\nMETRIC\nT1C0.8\n%\nX1.0Y1.0\nM30\n", "f.drl");
  ASSERT_EQ(first.holes.size(), 1u);
  expect_hole(first.holes[0], 1000000, 1000000, 800000, 1);
  bool warned = false;
  for (const std::string& n : first.notes)
    warned |= n.find(
                  "line 5: warning: a hole before any tool is selected: drilled with T1, the "
                  "only tool defined") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(ExcellonWriters, ToolsDefinedBeforeTheUnitLine) {  // PADS
  const PcbLayer l =
      read_excellon_text("M48\nT1C0.035\nT2C0.04\nINCH,LZ\n%\nT2\nX1.0Y0.5\nM30\n", "p.drl");
  ASSERT_EQ(l.holes.size(), 1u);
  expect_hole(l.holes[0], 25400000, 12700000, 1016000, 2);
  EXPECT_EQ(l.apertures_or_tools, 2);
}

TEST(ExcellonWriters, ToolSizesOnlyInAllegroHolesizeComments) {
  const PcbLayer l = read_excellon_text(
      "%\n;T1 Holesize 1. = 13.000000 Tolerance = +2.000000/-2.000000 PLATED MILS Quantity = 1\n"
      ";T02 Holesize 2. = 1.000000 Tolerance = +0.000000/-0.000000 NON_PLATED MM Quantity = 1\n"
      "M48\nINCH,LZ\n%\nT01\nX1.0Y1.0\nT02\nX2.0Y1.0\nM30\n",
      "allegro.drl");
  ASSERT_EQ(l.holes.size(), 2u);
  expect_hole(l.holes[0], 25400000, 25400000, 330200, 1);  // 13 mils
  expect_hole(l.holes[1], 50800000, 25400000, 1000000, 2);
}

TEST(ExcellonWriters, AnOversizeToolLeavesOutItsHolesNotTheFile) {
  // A 139.7 mm (5.5 in) "drill": a routed cut-out written as one tool.
  const PcbLayer l = read_excellon_text(
      "M48\nINCH,LZ\nT1C0.035\nT2C5.5\n%\nT1\nX1.0Y1.0\nT2\nX2.0Y2.0\nX3.0Y2.0\nT1\nX1.5Y1.0\n"
      "M30\n",
      "big.drl");
  ASSERT_EQ(l.holes.size(), 2u);
  EXPECT_EQ(l.holes[1].at.x, 38100000);
  EXPECT_TRUE(has_note(l,
                       "tool T2 (139.7 mm) is larger than 100 mm, not a drill: its 2 holes "
                       "left out"))
      << ::testing::PrintToString(l.notes);
}

// Excellon's repeat hole: "R3X2.0" drills the last hole 3 more times, 2 mm apart (refused as
// an unknown command; from the corpus).
TEST(ExcellonWriters, RepeatHoleDrillsTheLastHoleAgainStepByStep) {
  const PcbLayer l = read_excellon_text(
      "M48\nMETRIC\nT1C0.8\n%\nG90\nG05\nT1\nX1.0Y1.0\nR3X2.0\nR2Y-0.5X0.5\nM30\n", "r.drl");
  ASSERT_EQ(l.holes.size(), 6u);
  for (int k = 0; k < 4; ++k) expect_hole(l.holes[k], (1 + 2 * k) * 1000000, 1000000, 800000, 1);
  expect_hole(l.holes[4], 7500000, 500000, 800000, 1);
  expect_hole(l.holes[5], 8000000, 0, 800000, 1);
}

// A repeat hole before any hole has nothing to repeat (gerbv drills from wherever the tool
// is, (0, 0) at the start: holes nobody placed): refused at its line.
TEST(ExcellonWriters, ARepeatHoleBeforeAnyHoleIsRefusedAtItsLine) {
  try {
    read_excellon_text("M48\nMETRIC\nT1C0.8\n%\nG90\nG05\nT1\nR3X2.0\nX1.0Y1.0\nM30\n", "r.drl");
    ADD_FAILURE() << "read";
  } catch (const PcbReadError& e) {
    EXPECT_EQ(std::string(e.what()), "r.drl:8: repeat hole 'R3X2.0' before any hole to repeat");
  }
}

// The oversize tool's warning names the line that gave its size.
TEST(ExcellonWriters, AnOversizeToolsWarningNamesItsLine) {
  const PcbLayer l = read_excellon_text(
      "M48\nINCH,LZ\nT1C0.035\nT2C5.5\n%\nT1\nX1.0Y1.0\nT2\nX2.0Y2.0\nM30\n", "big.drl");
  EXPECT_TRUE(has_note(l,
                       "line 4: warning: tool T2 (139.7 mm) is larger than 100 mm, not a drill: "
                       "its 1 hole left out"))
      << ::testing::PrintToString(l.notes);
}

// Holes and slots are counted apart, in words ("its 3 hole(s) or slot(s)" for 2 holes and a
// slot).
TEST(ExcellonWriters, AnOversizeToolsWarningCountsHolesAndSlotsApart) {
  const PcbLayer l = read_excellon_text(
      "M48\nMETRIC\nT1C0.8\nT2C139.7\n%\nG90\nG05\nT1\nX1.0Y1.0\nT2\nX2.0Y2.0\nX3.0Y2.0\n"
      "G00X0Y0\nM15\nG01X50.0Y0\nM16\nM30\n",
      "big.drl");
  ASSERT_EQ(l.holes.size(), 1u);
  EXPECT_TRUE(l.slots.empty());
  EXPECT_TRUE(has_note(l,
                       "warning: tool T2 (139.7 mm) is larger than 100 mm, not a drill: its 2 "
                       "holes and 1 slot left out"))
      << ::testing::PrintToString(l.notes);
}

// When the only tool is over 100 mm nothing is left to drill: refused saying so (it said that
// no tool was defined, or read as an empty drill file and the board said "nothing to do").
TEST(ExcellonWriters, OnlyAnOversizeToolIsRefusedSayingSo) {
  for (const std::string& body : {std::string("T1\nX10.0Y10.0\n"), std::string("X10.0Y10.0\n")}) {
    try {
      read_excellon_text("M48\nMETRIC\nT1C139.7\n%\nG90\nG05\n" + body + "M30\n", "big.drl");
      ADD_FAILURE() << "read: " << body;
    } catch (const PcbReadError& e) {
      EXPECT_NE(std::string(e.what()).find(
                    "every hole and slot is of a tool larger than 100 mm, which is not a drill "
                    "(tool T1 (139.7 mm) is larger than 100 mm, not a drill: its 1 hole left "
                    "out): nothing is left to drill"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(ExcellonWriters, UnitsBeforeM48AndAPercentFirstLine) {  // old EAGLE .drd, Fritzing .txt
  const PcbLayer l =
      read_excellon_text("%\nINCH,TZ\nM48\nT1C0.032\n%\nT1\nX10000Y5000\nM30\n", "e.drd");
  ASSERT_EQ(l.holes.size(), 1u);
  expect_hole(l.holes[0], 25400000, 12700000, 812800, 1);  // 2.4, TZ: "10000" is 1.0000
}

TEST(ExcellonWriters, G93SetsTheWorkZero) {  // Mentor writes G93X0Y0
  const PcbLayer zero =
      read_excellon_text("M48\nMETRIC\nT1C0.8\n%\nG93X0Y0\nT1\nX1.0Y2.0\nM30\n", "m.drl");
  ASSERT_EQ(zero.holes.size(), 1u);
  expect_hole(zero.holes[0], 1000000, 2000000, 800000, 1);
  const PcbLayer moved =
      read_excellon_text("M48\nMETRIC\nT1C0.8\n%\nG93X10.0Y0\nT1\nX1.0Y2.0\nM30\n", "m.drl");
  ASSERT_EQ(moved.holes.size(), 1u);
  EXPECT_EQ(moved.holes[0].at.x, 11000000);
}

// Allegro route files: M16 (tool up) also with the next position on its line.
TEST(ExcellonWriters, M16EndsARouteAnywhere) {
  const PcbLayer l = read_excellon_text(
      "M48\nMETRIC\nT1C1.0\n%\nT1\nM16\nG00X1.0Y1.0\nM15\nG01X5.0Y1.0\nM16X6.0Y1.0\nM17\n"
      "G05\nX9.0Y9.0\nM30\n",
      "route.rou");
  ASSERT_EQ(l.slots.size(), 1u);
  EXPECT_EQ(l.slots[0].to.x, 5000000);
  ASSERT_EQ(l.holes.size(), 1u);
}

// A lone CR ends a line as LF does (gerbv's test-drill-leading-zero-1.exc ends
// "X001Y03\rM30\r\n"; refused before as "unexpected '\r'"); CR LF is one line end.
TEST(ExcellonWriters, ALoneCarriageReturnEndsALine) {
  const PcbLayer l = read_excellon_text(
      "M48\r\nINCH,LZ\r\nT13C0.05\r\n%\r\nT13\r\nX-001000Y030000\r\nX001Y03\rM30\r\nX05Y05\r\n",
      "z.exc");
  ASSERT_EQ(l.holes.size(), 2u);
  expect_hole(l.holes[1], 2540000, 76200000, 1270000, 13);  // INCH,LZ 2.4: "001" is 00.1
  try {  // line numbers count a lone CR as a line end, CR LF as one
    read_excellon_text("M48\r\nINCH,LZ\r\nT1C0.05\r%\r\nT1\rX001Q\r\nM30\r\n", "q.exc");
    ADD_FAILURE() << "read";
  } catch (const PcbReadError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("q.exc:6: ", 0), 0u) << e.what();
  }
}

// Blanks between the words of a coordinate line (gerbv's test-drill-spaces.exc, refused as
// "unexpected ' '"): skipped, as gerbv does, with a warning.
TEST(ExcellonWriters, BlanksInsideACoordinateLineAreSkipped) {
  const PcbLayer l = read_excellon_text(
      "M48\nINCH,LZ\nT13C0.05\n%\nT13\nX-001000 Y030000\nX001\tY03\nM30\n", "s.exc");
  ASSERT_EQ(l.holes.size(), 2u);
  expect_hole(l.holes[0], -2540000, 76200000, 1270000, 13);
  expect_hole(l.holes[1], 2540000, 76200000, 1270000, 13);
  EXPECT_TRUE(has_note(l, "line 6: warning: blanks inside a coordinate line ignored"))
      << ::testing::PrintToString(l.notes);
}

}  // namespace
}  // namespace host::pcb
