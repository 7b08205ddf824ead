// Operator panel contacts on RB8..RB14, active low (closed contact pulls the pin to GND;
// external pull-ups). Needs ADPCFG bits 8..14 set (digital), done by init_ports().
// Implements hal::PanelPins.
#ifndef HAL_DSPIC30F6014_PANEL_PINS_H
#define HAL_DSPIC30F6014_PANEL_PINS_H

#include <stdint.h>  // uint8_t

#include "hal/interfaces/panel_pins.h"  // hal::PanelPins

namespace dspic {

#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
// A concrete port object, never deleted through a base pointer.
class PanelPins : public hal::PanelPins {
 public:
  virtual uint8_t read_raw();
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_PANEL_PINS_H
