// A simulated HD44780's memory and modes (see hd44780_display.h).
#include "hal/fake/panel/hd44780_display.h"

#include <cstring>

namespace fake {

Hd44780Display::Hd44780Display()
    : address_counter_(0),
      address_in_cgram_(false),
      display_shift_(0),
      display_on_(false),
      cursor_on_(false),
      blink_on_(false),
      increment_(true),
      shift_on_write_(false),
      eight_bit_(true),
      two_lines_(false) {
  std::memset(ddram_, ' ', sizeof ddram_);
  std::memset(cgram_, 0, sizeof cgram_);
}

void Hd44780Display::clear() {
  std::memset(ddram_, ' ', sizeof ddram_);
  address_counter_ = 0;
  address_in_cgram_ = false;
  display_shift_ = 0;
  increment_ = true;
}

void Hd44780Display::return_home() {
  address_counter_ = 0;
  address_in_cgram_ = false;
  display_shift_ = 0;
}

void Hd44780Display::set_entry_mode(bool increment, bool shift_on_write) {
  increment_ = increment;
  shift_on_write_ = shift_on_write;
}

void Hd44780Display::set_display_control(bool display_on, bool cursor_on, bool blink_on) {
  display_on_ = display_on;
  cursor_on_ = cursor_on;
  blink_on_ = blink_on;
}

void Hd44780Display::shift(bool display, bool right) {
  if (display) {
    display_shift_ += right ? -1 : 1;
  } else {
    address_counter_ = step_address(address_counter_, right);
  }
}

void Hd44780Display::set_function(bool eight_bit, bool two_lines) {
  eight_bit_ = eight_bit;
  two_lines_ = two_lines;
}

void Hd44780Display::set_cgram_address(uint8_t address) {
  address_counter_ = address & 0x3F;
  address_in_cgram_ = true;
}

bool Hd44780Display::set_ddram_address(uint8_t address) {
  const bool holds_a_character = ddram_index(address) >= 0;
  address_counter_ = address;
  address_in_cgram_ = false;
  return holds_a_character;
}

void Hd44780Display::write_data(uint8_t byte) {
  if (address_in_cgram_) {
    cgram_[address_counter_ & 0x3F] = byte;
    address_counter_ = (uint8_t)((address_counter_ + (increment_ ? 1 : 0x3F)) & 0x3F);
    return;
  }
  const int index = ddram_index(address_counter_);
  if (index >= 0) ddram_[index] = byte;
  address_counter_ = step_address(address_counter_, increment_);
  if (shift_on_write_) display_shift_ += increment_ ? 1 : -1;
}

// Next DDRAM address; in 2-line mode the gap 0x28..0x3F is skipped (0x27 -> 0x40 ->...
// 0x67 -> 0x00).
uint8_t Hd44780Display::step_address(uint8_t address, bool up) const {
  if (!two_lines_) return (uint8_t)(up ? (address + 1) % 80 : (address + 79) % 80);
  if (up) {
    if (address == 0x27) return 0x40;
    if (address == 0x67) return 0x00;
    return (uint8_t)(address + 1);
  }
  if (address == 0x40) return 0x27;
  if (address == 0x00) return 0x67;
  return (uint8_t)(address - 1);
}

// Index into ddram_ (row * 40 + column), -1 for addresses that hold no character.
int Hd44780Display::ddram_index(uint8_t address) const {
  if (!two_lines_) return address < 80 ? address : -1;
  if (address <= 0x27) return address;
  if (address >= 0x40 && address <= 0x67) return 40 + (address - 0x40);
  return -1;
}

std::string Hd44780Display::visible_line(int row) const {
  std::string line(16, ' ');
  if (!display_on_ || row < 0 || row > 1 || (!two_lines_ && row == 1)) return line;
  for (int column = 0; column < 16; ++column) {
    const int shifted = ((column + display_shift_) % 40 + 40) % 40;
    line[column] = (char)ddram_[row * 40 + shifted];
  }
  return line;
}

std::string Hd44780Display::ddram(uint8_t first, uint8_t count) const {
  std::string out;
  uint8_t address = first;
  for (uint8_t i = 0; i < count; ++i) {
    const int index = ddram_index(address);
    out.push_back(index >= 0 ? (char)ddram_[index] : '?');
    address = step_address(address, true);
  }
  return out;
}

}  // namespace fake
