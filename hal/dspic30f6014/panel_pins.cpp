// Panel contacts from PORTB: RB8..RB14 are wired in hal::InputBits order.
#include "hal/dspic30f6014/panel_pins.h"

#include "hal/dspic30f6014/pins.h"           // kPanelFirstBit, kPanelMask
#include "hal/dspic30f6014/registers.h"      // PORTB
#include "hal/interfaces/operator_inputs.h"  // hal::InputBits

namespace dspic {

static_assert(hal::kJoyLeft == 0x01 && hal::kJoyRight == 0x02 && hal::kJoyDown == 0x04 &&
                  hal::kJoyUp == 0x08 && hal::kButtonZ == 0x10 && hal::kButtonConfirm == 0x20 &&
                  hal::kButtonClear == 0x40,
              "RB8..RB14 are wired in InputBits order");

// Inverts (active low) and shifts the contact bits down to InputBits.
uint8_t PanelPins::read_raw() {
  const uint16_t closed = (uint16_t)~PORTB::read() & pins::kPanelMask;
  return (uint8_t)(closed >> pins::kPanelFirstBit);
}

}  // namespace dspic
