// What a simulated HD44780 holds and shows: DDRAM, CGRAM, the address counter, the display
// shift and the modes the instructions set (entry mode, display control, function set).
// It knows nothing of the bus or of time: fake::Hd44780Model decodes the pins, checks the
// timing and calls these, one per instruction of the HD44780U data sheet's Table 6.
#ifndef HAL_FAKE_PANEL_HD44780_DISPLAY_H
#define HAL_FAKE_PANEL_HD44780_DISPLAY_H

#include <stdint.h>

#include <string>

namespace fake {

class Hd44780Display {
 public:
  // The state after the internal reset circuit (data sheet "Initialization by internal
  // reset circuit"): display off, increment, 8-bit, one line, DDRAM all spaces.
  Hd44780Display();

  // Instructions.
  void clear();
  void return_home();
  void set_entry_mode(bool increment, bool shift_on_write);
  void set_display_control(bool display_on, bool cursor_on, bool blink_on);
  void shift(bool display, bool right);  // display: shift the display, else move the cursor
  void set_function(bool eight_bit, bool two_lines);
  void set_cgram_address(uint8_t address);
  // False when the address holds no character in the current line mode (it is set anyway).
  bool set_ddram_address(uint8_t address);
  // A data write: into DDRAM or CGRAM where the address counter points, which then moves by
  // the entry mode.
  void write_data(uint8_t byte);

  // What an operator would read on a row: 16 characters, all spaces while display is off.
  std::string visible_line(int row) const;
  // Characters at DDRAM addresses [first, first + count) (2-line addressing).
  std::string ddram(uint8_t first, uint8_t count) const;
  uint8_t address_counter() const { return address_counter_; }
  bool display_on() const { return display_on_; }
  bool cursor_on() const { return cursor_on_; }
  bool blink_on() const { return blink_on_; }
  bool increment() const { return increment_; }
  bool shift_on_write() const { return shift_on_write_; }
  bool eight_bit() const { return eight_bit_; }
  bool two_lines() const { return two_lines_; }

 private:
  uint8_t step_address(uint8_t address, bool up) const;
  int ddram_index(uint8_t address) const;

  uint8_t ddram_[80];
  uint8_t cgram_[64];
  uint8_t address_counter_;
  bool address_in_cgram_;
  int display_shift_;
  bool display_on_, cursor_on_, blink_on_, increment_, shift_on_write_, eight_bit_, two_lines_;
};

}  // namespace fake

#endif  // HAL_FAKE_PANEL_HD44780_DISPLAY_H
