// HD44780 driver: the data sheet's 8-bit initialisation and text output with fixed delays.
#include "hal/drivers/hd44780/hd44780.h"

namespace drivers {

Hd44780::Hd44780(hal::LcdBus* bus) : bus_(bus) {}

// 8-bit "Initializing by Instruction": works whatever state the internal reset left.
void Hd44780::init() {
  bus_->set_control(0);
  bus_->set_data(0);
  bus_->delay_us(kPowerOnWaitUs);
  // Each instruction and its wait, as a table (less code than a call each).
  struct Step {
    uint8_t code;
    uint16_t wait_us;
  };
  static const Step kSteps[] = {
      {kFunctionSet8Bit, kFirstFunctionSetWaitUs}, {kFunctionSet8Bit, kSecondFunctionSetWaitUs},
      {kFunctionSet8Bit, kInstructionWaitUs},      {kFunctionSet8Bit2Lines, kInstructionWaitUs},
      {kDisplayOff, kInstructionWaitUs},           {kClearDisplay, kClearHomeWaitUs},
      {kEntryModeIncrement, kInstructionWaitUs},   {kDisplayOnCursorOff, kInstructionWaitUs}};
  for (uint8_t i = 0; i < (uint8_t)(sizeof kSteps / sizeof kSteps[0]); ++i)
    write_instruction(kSteps[i].code, kSteps[i].wait_us);
}

// Rewrites a whole row so stale characters never survive.
void Hd44780::write_line(uint8_t row, const char* text) {
  if (row >= kRows) return;
  set_cursor(row, 0);
  const char* p = text;
  for (uint8_t column = 0; column < kColumns; ++column) {
    char c = ' ';
    if (p != 0 && *p != '\0') c = *p++;
    write_char(c);
  }
}

// Blank screen, cursor home.
void Hd44780::clear() {
  write_instruction(kClearDisplay, kClearHomeWaitUs);
}

// Cursor home, display shift undone.
void Hd44780::home() {
  write_instruction(kReturnHome, kClearHomeWaitUs);
}

// Set DDRAM address: rows start at 0x00 and 0x40 in 2-line mode.
void Hd44780::set_cursor(uint8_t row, uint8_t column) {
  if (row >= kRows || column >= kColumns) return;
  const uint8_t base = row == 0 ? kRow0Address : kRow1Address;
  write_instruction((uint8_t)(kSetDdramAddress | (base + column)), kInstructionWaitUs);
}

// Codes below 0x20 would show the (uninitialised) CGRAM glyphs, so they become spaces.
void Hd44780::write_char(char c) {
  uint8_t code = (uint8_t)c;
  if (code < 0x20) code = ' ';
  strobe(hal::LcdBus::kRs, code);
  bus_->delay_us(kInstructionWaitUs);
}

// One instruction, then its execution time (the busy flag is never read).
void Hd44780::write_instruction(uint8_t code, uint16_t wait_us) {
  strobe(0, code);
  bus_->delay_us(wait_us);
}

// Write cycle: RS and data set up, E high long enough, data latched on E's falling edge.
void Hd44780::strobe(uint8_t rs, uint8_t byte) {
  bus_->set_control(rs);
  bus_->set_data(byte);
  bus_->delay_us(kStrobeUs);
  bus_->set_control((uint8_t)(rs | hal::LcdBus::kE));
  bus_->delay_us(kStrobeUs);
  bus_->set_control(rs);
}

}  // namespace drivers
