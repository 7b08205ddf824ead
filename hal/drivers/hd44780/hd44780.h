// HD44780 two-line character LCD on an 8-bit bus (write-only: R/W held low, fixed delays
// instead of polling the busy flag). Implements hal::TextDisplay over hal::LcdBus.
#ifndef HAL_DRIVERS_HD44780_HD44780_H
#define HAL_DRIVERS_HD44780_HD44780_H

#include <stdint.h>  // uint8_t, uint16_t

#include "hal/interfaces/lcd_bus.h"       // hal::LcdBus
#include "hal/interfaces/text_display.h"  // hal::TextDisplay

namespace drivers {

// A concrete driver, never deleted through a base pointer (no heap): the host build's
// -Wnon-virtual-dtor is silenced for it (GCC >= 5; XC16's GCC 4.5 builds without it).
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
class Hd44780 : public hal::TextDisplay {
 public:
  // Waits, all from the HD44780U data sheet ("Initializing by Instruction", Table 6, at
  // f_OSC 270 kHz) with margin for slower clones (1.64 ms / 40 us at 250 kHz).
  enum {
    kPowerOnWaitUs = 50000,          // > 15 ms after VCC 4.5 V (> 40 ms at 2.7 V, clones ~50 ms)
    kFirstFunctionSetWaitUs = 5000,  // > 4.1 ms
    kSecondFunctionSetWaitUs = 200,  // > 100 us
    kInstructionWaitUs = 50,         // 37 us (40 us at 250 kHz)
    kClearHomeWaitUs = 2000,         // 1.52 ms (1.64 ms at 250 kHz)
    kStrobeUs = 1                    // t_AS 40 ns, PW_EH 230 ns, t_DSW 80 ns: 1 us covers 3 V parts
  };
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif
  // Instruction codes (Table 6).
  enum {
    kClearDisplay = 0x01,
    kReturnHome = 0x02,
    kEntryModeIncrement = 0x06,  // I/D = 1, S = 0
    kDisplayOff = 0x08,
    kDisplayOnCursorOff = 0x0C,     // D = 1, C = 0, B = 0
    kFunctionSet8Bit = 0x30,        // DL = 1 (N, F not yet taken)
    kFunctionSet8Bit2Lines = 0x38,  // DL = 1, N = 1, F = 0 (5x8)
    kSetDdramAddress = 0x80
  };
  // DDRAM address of column 0 of each row in 2-line mode.
  enum { kRow0Address = 0x00, kRow1Address = 0x40 };

  explicit Hd44780(hal::LcdBus* bus);
  // Full 8-bit initialisation by instruction; call once after power-up, before any other.
  void init();
  // TextDisplay: one row, padded with spaces to kColumns; control characters show as spaces.
  virtual void write_line(uint8_t row, const char* text);
  virtual void clear();
  // Cursor (DDRAM address) to row 0 column 0 and undoes any display shift.
  void home();
  // Moves the address counter; out-of-range rows or columns are ignored.
  void set_cursor(uint8_t row, uint8_t column);
  // Writes one character at the cursor (which then advances).
  void write_char(char c);

 private:
  void write_instruction(uint8_t code, uint16_t wait_us);
  void strobe(uint8_t rs, uint8_t byte);

  hal::LcdBus* bus_;
};

}  // namespace drivers

#endif  // HAL_DRIVERS_HD44780_HD44780_H
