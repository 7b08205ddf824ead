// Host-only simulated HD44780 behind a hal::LcdBus: decodes the pin activity the driver
// produces into instructions and data, keeps DDRAM, the address counter and the modes, and
// checks the data sheet's timing (power-on wait, init gaps, busy times, write-cycle setup).
// Time only advances in delay_us(); pin changes take no time, so every gap the data sheet
// asks for must come from an explicit delay.
#ifndef HAL_FAKE_PANEL_FAKE_HD44780_H
#define HAL_FAKE_PANEL_FAKE_HD44780_H

#include <stdint.h>

#include <string>
#include <vector>

#include "hal/interfaces/lcd_bus.h"

namespace fake {

class Hd44780Model : public hal::LcdBus {
 public:
  // Minimum times in ns (HD44780U data sheet: init by instruction, Table 6 at 270 kHz,
  // bus timing at 4.5-5.5 V).
  static const uint64_t kPowerOnNs = 15000000;       // before the first instruction
  static const uint64_t kInitGap1Ns = 4100000;       // first to second 0x3x
  static const uint64_t kInitGap2Ns = 100000;        // second to third 0x3x
  static const uint64_t kExecNs = 37000;             // most instructions and data writes
  static const uint64_t kClearHomeExecNs = 1520000;  // clear display, return home
  static const uint64_t kEnableHighNs = 230;         // PW_EH
  static const uint64_t kEnableCycleNs = 500;        // t_cycE
  static const uint64_t kAddressSetupNs = 40;        // t_AS: RS, R/W before E rises
  static const uint64_t kDataSetupNs = 80;           // t_DSW: data before E falls

  // One write cycle as the controller latched it.
  struct Latch {
    uint64_t time_ns;  // at E's falling edge
    bool rs;           // true = data register
    uint8_t byte;
  };

  Hd44780Model();

  // hal::LcdBus
  void set_control(uint8_t control_bits) override;
  void set_data(uint8_t byte) override;
  void delay_us(uint16_t us) override;

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
  // True once the three 0x3x function sets arrived with the data sheet's waits.
  bool initialised_by_instruction() const { return init_step_ == kInitDone; }

  uint64_t now_ns() const { return now_ns_; }
  const std::vector<Latch>& latches() const { return latches_; }
  // Human-readable timing and protocol violations, empty when the driver behaved.
  const std::vector<std::string>& violations() const { return violations_; }

 private:
  enum InitStep { kPowerOn, kAfterFirst, kAfterSecond, kInitDone };
  void latch(bool rs, uint8_t byte);
  void instruction(uint8_t code);
  void write_data(uint8_t byte);
  uint8_t step_address(uint8_t address, bool up) const;
  int ddram_index(uint8_t address) const;
  void violation(const std::string& what);

  uint64_t now_ns_;
  uint8_t control_;
  uint8_t data_;
  uint64_t control_changed_ns_;
  uint64_t data_changed_ns_;
  uint64_t enable_rose_ns_;
  bool enable_seen_;
  uint64_t busy_until_ns_;
  InitStep init_step_;
  uint64_t last_init_latch_ns_;

  uint8_t ddram_[80];
  uint8_t cgram_[64];
  uint8_t address_counter_;
  bool address_in_cgram_;
  int display_shift_;
  bool display_on_, cursor_on_, blink_on_, increment_, shift_on_write_, eight_bit_, two_lines_;

  std::vector<Latch> latches_;
  std::vector<std::string> violations_;
};

}  // namespace fake

#endif  // HAL_FAKE_PANEL_FAKE_HD44780_H
