// The operator panel, debounced: joystick directions, Z toggle, confirm, clear.
#ifndef HAL_INTERFACES_OPERATOR_INPUTS_H
#define HAL_INTERFACES_OPERATOR_INPUTS_H

#include <stdint.h>  // uint8_t

namespace hal {

enum InputBits {
  kJoyLeft = 0x01,
  kJoyRight = 0x02,
  kJoyDown = 0x04,   // towards the operator (-Y), or -Z while the Z toggle is on
  kJoyUp = 0x08,
  kButtonZ = 0x10,   // held: the joystick drives Z
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
