// The operator panel's raw input pins (joystick contacts and buttons), not debounced.
// The port maps its pins and their polarity; the panel driver debounces.
#ifndef HAL_INTERFACES_PANEL_PINS_H
#define HAL_INTERFACES_PANEL_PINS_H

#include <stdint.h>  // uint8_t

namespace hal {

class PanelPins {
 public:
  // One sample of every contact as hal::InputBits (operator_inputs.h), 1 = contact closed.
  virtual uint8_t read_raw() = 0;

 protected:
  ~PanelPins() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_PANEL_PINS_H
