// Operator panel inputs: per-contact debouncing of the raw pins (hal::PanelPins), joystick
// sanity (opposite directions cancel), and the Z button as "held" or "toggle".
// Implements hal::OperatorInputs. tick_1ms() samples; call it from the 1 ms tick.
#ifndef HAL_DRIVERS_OPERATOR_PANEL_OPERATOR_PANEL_H
#define HAL_DRIVERS_OPERATOR_PANEL_OPERATOR_PANEL_H

#include <stdint.h>  // uint8_t

#include "hal/interfaces/operator_inputs.h"  // hal::OperatorInputs, hal::InputBits
#include "hal/interfaces/panel_pins.h"       // hal::PanelPins

namespace drivers {

// A concrete driver, never deleted through a base pointer (no heap): the host build's
// -Wnon-virtual-dtor is silenced for it (GCC >= 5; XC16's GCC 4.5 builds without it).
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
class OperatorPanel : public hal::OperatorInputs {
 public:
  enum { kContactCount = 7, kDefaultDebounceMs = 5 };
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif
  enum ZMode {
    // kButtonZ reported while the button is pressed, as hal::InputBits defines it: what the
    // firmware uses (app::JogController toggles Z mode on each press).
    kZHeld = 0,
    // The panel latches: each press switches kButtonZ on or off. Only for a consumer that
    // reads kButtonZ as a level; with the firmware's JogController, which toggles on each
    // rising edge, only every second press would change Z mode.
    kZToggle = 1
  };

  // debounce_ms: consecutive 1 ms samples a contact must differ from its debounced state
  // before the change is taken (1..255; 0 counts as 1).
  OperatorPanel(hal::PanelPins* pins, ZMode z_mode, uint8_t debounce_ms);
  // Takes one raw sample and updates the debounced state.
  void tick_1ms();
  // hal::OperatorInputs: debounced InputBits after joystick sanity and the Z mode.
  virtual uint8_t state();
  // Debounced contacts as wired, before joystick sanity and the Z mode.
  uint8_t contacts() const {
    return stable_;
  }

 private:
  hal::PanelPins* pins_;
  uint8_t z_mode_;
  uint8_t debounce_ms_;
  uint8_t stable_;
  uint8_t z_on_;
  uint8_t differing_ms_[kContactCount];
};

}  // namespace drivers

#endif  // HAL_DRIVERS_OPERATOR_PANEL_OPERATOR_PANEL_H
