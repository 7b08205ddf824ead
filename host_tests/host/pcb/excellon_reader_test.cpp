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

}  // namespace
}  // namespace host::pcb
