// The HD44780's pins as a driver sees them: RS, R/W, E, DB7..DB0 and a microsecond delay.
// Implemented by the dsPIC port (LATD pins) and on the host by a simulated HD44780.
#ifndef HAL_INTERFACES_LCD_BUS_H
#define HAL_INTERFACES_LCD_BUS_H

#include <stdint.h>  // uint8_t, uint16_t

namespace hal {

class LcdBus {
 public:
  // Control line bits for set_control().
  enum ControlBits {
    kRs = 0x01,  // 0 = instruction register, 1 = data register
    kRw = 0x02,  // 0 = write, 1 = read (the drivers only write)
    kE = 0x04    // enable; the controller latches DB7..DB0 on its falling edge
  };
  // Drives RS, R/W and E to the levels given as ControlBits.
  virtual void set_control(uint8_t control_bits) = 0;
  // Drives DB7..DB0.
  virtual void set_data(uint8_t byte) = 0;
  // Busy-waits at least this many microseconds.
  virtual void delay_us(uint16_t us) = 0;

 protected:
  ~LcdBus() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_LCD_BUS_H
