// HD44780 driver: init sequence and its timing, text placement, as a simulated controller
// decodes them from the bus.
#include "hal/drivers/hd44780/hd44780.h"

#include <gtest/gtest.h>

#include "hal/fake/panel/fake_hd44780.h"

namespace {

class Hd44780Test : public ::testing::Test {
 protected:
  Hd44780Test() : lcd(&model) {}
  fake::Hd44780Model model;
  drivers::Hd44780 lcd;
};

const uint64_t kMs = 1000000, kUs = 1000;

TEST_F(Hd44780Test, InitSendsTheDataSheetSequence) {
  lcd.init();
  const uint8_t expected[] = {0x30, 0x30, 0x30, 0x38, 0x08, 0x01, 0x06, 0x0C};
  ASSERT_EQ(model.latches().size(), sizeof expected);
  for (size_t i = 0; i < sizeof expected; ++i) {
    EXPECT_FALSE(model.latches()[i].rs) << i;
    EXPECT_EQ(model.latches()[i].byte, expected[i]) << i;
  }
}

TEST_F(Hd44780Test, InitWaitsAtLeast15msAfterPowerOn) {
  lcd.init();
  EXPECT_GE(model.latches().at(0).time_ns, 15 * kMs);
}

TEST_F(Hd44780Test, InitGapsBetweenFunctionSetsMeetDataSheet) {
  lcd.init();
  const auto& l = model.latches();
  EXPECT_GE(l.at(1).time_ns - l.at(0).time_ns, 4100 * kUs);
  EXPECT_GE(l.at(2).time_ns - l.at(1).time_ns, 100 * kUs);
  EXPECT_TRUE(model.initialised_by_instruction());
}

TEST_F(Hd44780Test, ClearDuringInitGetsItsFullExecutionTime) {
  lcd.init();
  const auto& l = model.latches();
  EXPECT_EQ(l.at(5).byte, 0x01);
  EXPECT_GE(l.at(6).time_ns - l.at(5).time_ns, 1520 * kUs);
}

TEST_F(Hd44780Test, InitLeavesTwoLineDisplayOnCursorOffIncrementing) {
  lcd.init();
  EXPECT_TRUE(model.eight_bit());
  EXPECT_TRUE(model.two_lines());
  EXPECT_TRUE(model.display_on());
  EXPECT_FALSE(model.cursor_on());
  EXPECT_FALSE(model.blink_on());
  EXPECT_TRUE(model.increment());
  EXPECT_FALSE(model.shift_on_write());
  EXPECT_EQ(model.address_counter(), 0);
  EXPECT_EQ(model.visible_line(0), std::string(16, ' '));
  EXPECT_EQ(model.visible_line(1), std::string(16, ' '));
}

TEST_F(Hd44780Test, InitAndTextBreakNoTimingRule) {
  lcd.init();
  lcd.write_line(0, "ENGRAVER");
  lcd.write_line(1, "READY");
  lcd.clear();
  lcd.home();
  lcd.write_char('A');
  EXPECT_TRUE(model.violations().empty()) << model.violations().front();
}

TEST_F(Hd44780Test, WriteLineRow0StartsAtDdram00) {
  lcd.init();
  lcd.write_line(0, "HELLO");
  EXPECT_EQ(model.visible_line(0), "HELLO           ");
  EXPECT_EQ(model.visible_line(1), "                ");
}

TEST_F(Hd44780Test, WriteLineRow1StartsAtDdram40) {
  lcd.init();
  lcd.write_line(1, "WORLD");
  EXPECT_EQ(model.ddram(0x40, 5), "WORLD");
  EXPECT_EQ(model.visible_line(1), "WORLD           ");
}

TEST_F(Hd44780Test, WriteLinePadsOverOldText) {
  lcd.init();
  lcd.write_line(0, "0123456789ABCDEF");
  lcd.write_line(0, "AB");
  EXPECT_EQ(model.visible_line(0), "AB              ");
}

TEST_F(Hd44780Test, WriteLineCutsTextAt16Columns) {
  lcd.init();
  lcd.write_line(0, "0123456789ABCDEFGHIJ");
  EXPECT_EQ(model.visible_line(0), "0123456789ABCDEF");
  EXPECT_EQ(model.ddram(0x10, 4), "    ");  // nothing spilled past the visible window
}

TEST_F(Hd44780Test, WriteLineIgnoresRowsPastTheSecond) {
  lcd.init();
  const size_t before = model.latches().size();
  lcd.write_line(2, "NOPE");
  EXPECT_EQ(model.latches().size(), before);
}

TEST_F(Hd44780Test, WriteLineTreatsNullTextAsEmpty) {
  lcd.init();
  lcd.write_line(0, "XXXX");
  lcd.write_line(0, nullptr);
  EXPECT_EQ(model.visible_line(0), std::string(16, ' '));
}

TEST_F(Hd44780Test, ControlCharactersShowAsSpaces) {
  lcd.init();
  lcd.write_line(0,
                 "A\tB\x01"
                 "C");
  EXPECT_EQ(model.visible_line(0), "A B C           ");
}

TEST_F(Hd44780Test, ClearBlanksBothRowsAndHomesTheCursor) {
  lcd.init();
  lcd.write_line(0, "ONE");
  lcd.write_line(1, "TWO");
  lcd.clear();
  EXPECT_EQ(model.visible_line(0), std::string(16, ' '));
  EXPECT_EQ(model.visible_line(1), std::string(16, ' '));
  EXPECT_EQ(model.address_counter(), 0);
}

TEST_F(Hd44780Test, SetCursorPlacesTheNextCharacter) {
  lcd.init();
  lcd.set_cursor(1, 15);
  lcd.write_char('Z');
  EXPECT_EQ(model.visible_line(1), "               Z");
}

TEST_F(Hd44780Test, SetCursorIgnoresColumnsPastTheEnd) {
  lcd.init();
  lcd.set_cursor(0, 3);
  lcd.set_cursor(0, 16);
  lcd.write_char('Q');
  EXPECT_EQ(model.visible_line(0), "   Q            ");
}

TEST_F(Hd44780Test, HomeMovesTheCursorToRow0Column0) {
  lcd.init();
  lcd.set_cursor(1, 4);
  lcd.home();
  lcd.write_char('H');
  EXPECT_EQ(model.visible_line(0), "H               ");
}

}  // namespace
