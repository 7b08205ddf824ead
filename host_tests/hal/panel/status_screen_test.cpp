// Status screen: fixed-column layout and millimetre formatting.
#include "hal/drivers/hd44780/status_screen.h"

#include <gtest/gtest.h>

#include <string>

namespace {

std::string mm(int32_t um) {
  char out[drivers::kMmFieldChars];
  drivers::format_mm(um, out);
  return std::string(out, sizeof out);
}

TEST(FormatMm, PrintsTwoDecimalsRightAligned) {
  EXPECT_EQ(mm(12500), " 12.50");
}
TEST(FormatMm, PrintsZero) {
  EXPECT_EQ(mm(0), "  0.00");
}
TEST(FormatMm, PrintsSubMillimetreWithLeadingZero) {
  EXPECT_EQ(mm(70), "  0.07");
}
TEST(FormatMm, RoundsHalfAwayFromZero) {
  EXPECT_EQ(mm(1005), "  1.01");
  EXPECT_EQ(mm(-1005), " -1.01");
}
TEST(FormatMm, PrintsNegativeWithSignBeforeDigits) {
  EXPECT_EQ(mm(-1250), " -1.25");
}
TEST(FormatMm, PrintsTheWidestValues) {
  EXPECT_EQ(mm(999994), "999.99");
  EXPECT_EQ(mm(-99994), "-99.99");
}
TEST(FormatMm, MarksValuesThatDoNotFit) {
  EXPECT_EQ(mm(999995), "######");
  EXPECT_EQ(mm(-99995), "######");
  EXPECT_EQ(mm(INT32_MIN), "######");
  EXPECT_EQ(mm(INT32_MAX), "######");
}

TEST(FormatStatus, LaysOutStateZThenXY) {
  drivers::StatusView v = {"RUN", {12500, 210000, -1250}};
  char row0[17], row1[17];
  drivers::format_status(v, row0, row1);
  EXPECT_STREQ(row0, "RUN      Z -1.25");
  EXPECT_STREQ(row1, "X 12.50  Y210.00");
}

TEST(FormatStatus, CutsLongStateNamesAt8) {
  drivers::StatusView v = {"ZEROING-X", {0, 0, 0}};
  char row0[17], row1[17];
  drivers::format_status(v, row0, row1);
  EXPECT_EQ(std::string(row0).substr(0, 9), "ZEROING- ");
}

TEST(FormatStatus, NullStateIsBlank) {
  drivers::StatusView v = {nullptr, {0, 0, 0}};
  char row0[17], row1[17];
  drivers::format_status(v, row0, row1);
  EXPECT_EQ(std::string(row0).substr(0, 9), "         ");
}

class RecordingDisplay : public hal::TextDisplay {
 public:
  void write_line(uint8_t row, const char* text) override { rows[row & 1] = text; }
  void clear() override {}
  std::string rows[2];
};

TEST(ShowStatus, WritesBothRows) {
  RecordingDisplay d;
  drivers::StatusView v = {"IDLE", {0, 0, 0}};
  drivers::show_status(&d, v);
  EXPECT_EQ(d.rows[0], "IDLE     Z  0.00");
  EXPECT_EQ(d.rows[1], "X  0.00  Y  0.00");
}

}  // namespace
