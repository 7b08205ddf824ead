// The operator panel, debounced: joystick directions, Z toggle, confirm, clear.
#ifndef HAL_INTERFACES_OPERATOR_INPUTS_H
#define HAL_INTERFACES_OPERATOR_INPUTS_H

#include <stdint.h>  // uint8_t

namespace hal {

enum InputBits {
  kJoyLeft = 0x01,
  kJoyRight = 0x02,
  kJoyDown = 0x04,  // towards the operator (-Y), or -Z while Z mode is on (see kButtonZ)
  kJoyUp = 0x08,
  // The Z toggle button, set while it is pressed (momentary); the application switches Z
  // mode (joystick down/up drive Z instead of Y) on each press, so a panel must not latch it.
  kButtonZ = 0x10,
  kButtonConfirm = 0x20,
  kButtonClear = 0x40
};

class OperatorInputs {
 public:
  // Debounced state as InputBits (1 = pressed). Called from the 1 ms tick.
  virtual uint8_t state() = 0;

 protected:
  ~OperatorInputs() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_OPERATOR_INPUTS_H
