// Host-only simulated HD44780 behind a hal::LcdBus: decodes the pin activity the driver
// produces into instructions and data, hands them to its Hd44780Display (DDRAM, the address
// counter and the modes: hd44780_display.h), and checks the data sheet's timing (power-on
// wait, init gaps, busy times, write-cycle setup). Time only advances in delay_us(); pin
// changes take no time, so every gap the data sheet asks for must come from an explicit delay.
#ifndef HAL_FAKE_PANEL_FAKE_HD44780_H
#define HAL_FAKE_PANEL_FAKE_HD44780_H

#include <stdint.h>

#include <string>
#include <vector>

#include "hal/fake/panel/hd44780_display.h"
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
  std::string visible_line(int row) const { return display_.visible_line(row); }
  // Characters at DDRAM addresses [first, first + count) (2-line addressing).
  std::string ddram(uint8_t first, uint8_t count) const { return display_.ddram(first, count); }
  const Hd44780Display& display() const { return display_; }
  uint8_t address_counter() const { return display_.address_counter(); }
  bool display_on() const { return display_.display_on(); }
  bool cursor_on() const { return display_.cursor_on(); }
  bool blink_on() const { return display_.blink_on(); }
  bool increment() const { return display_.increment(); }
  bool shift_on_write() const { return display_.shift_on_write(); }
  bool eight_bit() const { return display_.eight_bit(); }
  bool two_lines() const { return display_.two_lines(); }
  // True once the three 0x3x function sets arrived with the data sheet's waits.
  bool initialised_by_instruction() const { return init_step_ == kInitDone; }

  uint64_t now_ns() const { return now_ns_; }
  const std::vector<Latch>& latches() const { return latches_; }
  // Human-readable timing and protocol violations, empty when the driver behaved.
  const std::vector<std::string>& violations() const { return violations_; }

 private:
  enum InitStep { kPowerOn, kAfterFirst, kAfterSecond, kInitDone };
  // The bus as the controller last saw it: the pin levels and when they changed.
  struct BusPins {
    uint8_t control = 0;  // hal::LcdBus control bits (RS, R/W, E)
    uint8_t data = 0;
    uint64_t control_changed_ns = 0;  // RS or R/W
    uint64_t data_changed_ns = 0;
    uint64_t enable_rose_ns = 0;
    bool enable_seen = false;  // E has risen at least once
  };
  void latch(bool rs, uint8_t byte);
  void instruction(uint8_t code);
  void violation(const std::string& what);

  uint64_t now_ns_;
  BusPins pins_;
  uint64_t busy_until_ns_;
  InitStep init_step_;
  uint64_t last_init_latch_ns_;
  Hd44780Display display_;

  std::vector<Latch> latches_;
  std::vector<std::string> violations_;
};

}  // namespace fake

#endif  // HAL_FAKE_PANEL_FAKE_HD44780_H
