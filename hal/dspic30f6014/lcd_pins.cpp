// LCD bus pins on LATD (pin map in pins.h).
#include "hal/dspic30f6014/lcd_pins.h"

#include "hal/dspic30f6014/clock.h"      // delay_us
#include "hal/dspic30f6014/pins.h"       // kLcdRsBit, kLcdRwBit, kLcdEBit
#include "hal/dspic30f6014/registers.h"  // LATD

namespace dspic {

// RS, R/W, E to RD8, RD9, RD10 in one write, so they change together.
void LcdPins::set_control(uint8_t control_bits) {
  uint16_t levels = 0;
  if (control_bits & kRs) levels |= bit(pins::kLcdRsBit);
  if (control_bits & kRw) levels |= bit(pins::kLcdRwBit);
  if (control_bits & kE) levels |= bit(pins::kLcdEBit);
  const uint16_t lines = bit(pins::kLcdRsBit) | bit(pins::kLcdRwBit) | bit(pins::kLcdEBit);
  LATD::modify(lines, levels);
}

// DB7..DB0 with one byte write to LATD<7:0>.
void LcdPins::set_data(uint8_t byte) {
  LATD::write_low_byte(byte);
}

void LcdPins::delay_us(uint16_t us) {
  dspic::delay_us(us);
}

}  // namespace dspic
