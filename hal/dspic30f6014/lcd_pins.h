// The LCD's bus on port D: DB0..DB7 = RD0..RD7 (one byte write to LATD<7:0>), RS = RD8,
// R/W = RD9, E = RD10. Only the main loop writes LATD, so its read-modify-writes are safe.
// Implements hal::LcdBus.
#ifndef HAL_DSPIC30F6014_LCD_PINS_H
#define HAL_DSPIC30F6014_LCD_PINS_H

#include <stdint.h>  // uint8_t, uint16_t

#include "hal/interfaces/lcd_bus.h"  // hal::LcdBus

namespace dspic {

#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
// A concrete port object, never deleted through a base pointer.
class LcdPins : public hal::LcdBus {
 public:
  virtual void set_control(uint8_t control_bits);
  virtual void set_data(uint8_t byte);
  virtual void delay_us(uint16_t us);
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_LCD_PINS_H
