// The simulated HD44780 itself: it must catch the mistakes the driver tests rely on it to
// catch, and decode addresses like the data sheet says.
#include "hal/fake/panel/fake_hd44780.h"

#include <gtest/gtest.h>

namespace {

// One write cycle with generous timing, then a wait.
void write(fake::Hd44780Model& m, bool rs, uint8_t byte, uint16_t wait_us) {
  const uint8_t r = rs ? hal::LcdBus::kRs : 0;
  m.set_control(r);
  m.set_data(byte);
  m.delay_us(1);
  m.set_control(r | hal::LcdBus::kE);
  m.delay_us(1);
  m.set_control(r);
  m.delay_us(wait_us);
}

void init_2line(fake::Hd44780Model& m) {
  m.delay_us(20000);
  write(m, false, 0x30, 5000);
  write(m, false, 0x30, 200);
  write(m, false, 0x30, 50);
  write(m, false, 0x38, 50);
  write(m, false, 0x0C, 50);
}

TEST(Hd44780Model, AcceptsACorrectInitialisation) {
  fake::Hd44780Model m;
  init_2line(m);
  EXPECT_TRUE(m.initialised_by_instruction());
  EXPECT_TRUE(m.violations().empty());
}

TEST(Hd44780Model, ReportsFirstInstructionBefore15ms) {
  fake::Hd44780Model m;
  m.delay_us(10000);
  write(m, false, 0x30, 5000);
  EXPECT_FALSE(m.violations().empty());
  EXPECT_FALSE(m.initialised_by_instruction());
}

TEST(Hd44780Model, ReportsSecondFunctionSetSoonerThan4_1ms) {
  fake::Hd44780Model m;
  m.delay_us(20000);
  write(m, false, 0x30, 4000);
  write(m, false, 0x30, 200);
  EXPECT_FALSE(m.violations().empty());
}

TEST(Hd44780Model, ReportsAWriteWhileBusyAfterClear) {
  fake::Hd44780Model m;
  init_2line(m);
  write(m, false, 0x01, 1000);  // clear needs 1.52 ms
  write(m, true, 'A', 50);
  ASSERT_EQ(m.violations().size(), 1u);
}

TEST(Hd44780Model, ReportsAnEnablePulseWithoutWidth) {
  fake::Hd44780Model m;
  init_2line(m);
  m.set_control(hal::LcdBus::kRs);
  m.set_data('A');
  m.delay_us(1);
  m.set_control(hal::LcdBus::kRs | hal::LcdBus::kE);
  m.set_control(hal::LcdBus::kRs);
  EXPECT_FALSE(m.violations().empty());
}

TEST(Hd44780Model, ReportsRsChangingWhileEnableIsHigh) {
  fake::Hd44780Model m;
  init_2line(m);
  m.delay_us(1);
  m.set_control(hal::LcdBus::kE);
  m.set_control(hal::LcdBus::kE | hal::LcdBus::kRs);
  EXPECT_FALSE(m.violations().empty());
}

TEST(Hd44780Model, AutoIncrementSkipsFrom27To40InTwoLineMode) {
  fake::Hd44780Model m;
  init_2line(m);
  write(m, false, 0x80 | 0x27, 50);
  write(m, true, 'a', 50);
  EXPECT_EQ(m.address_counter(), 0x40);
  write(m, true, 'b', 50);
  EXPECT_EQ(m.ddram(0x27, 2), "ab");
}

TEST(Hd44780Model, DisplayOffShowsBlankRows) {
  fake::Hd44780Model m;
  init_2line(m);
  write(m, true, 'X', 50);
  write(m, false, 0x08, 50);
  EXPECT_EQ(m.visible_line(0), std::string(16, ' '));
}

}  // namespace
