// Operator panel: debouncing by consecutive samples, so one bounce restarts the count.
#include "hal/drivers/operator_panel/operator_panel.h"

namespace drivers {

OperatorPanel::OperatorPanel(hal::PanelPins* pins, ZMode z_mode, uint8_t debounce_ms)
    : pins_(pins),
      z_mode_((uint8_t)z_mode),
      debounce_ms_(debounce_ms == 0 ? 1 : debounce_ms),
      stable_(0),
      z_on_(0) {
  for (uint8_t i = 0; i < kContactCount; ++i) differing_ms_[i] = 0;
}

// A contact changes state after debounce_ms consecutive samples that disagree with it.
void OperatorPanel::tick_1ms() {
  const uint8_t raw = pins_->read_raw();
  uint8_t pressed_now = 0;
  for (uint8_t i = 0; i < kContactCount; ++i) {
    const uint8_t mask = (uint8_t)(1u << i);
    if ((raw & mask) == (stable_ & mask)) {
      differing_ms_[i] = 0;
      continue;
    }
    if (++differing_ms_[i] < debounce_ms_) continue;
    differing_ms_[i] = 0;
    stable_ ^= mask;
    if (stable_ & mask) pressed_now |= mask;
  }
  if (pressed_now & hal::kButtonZ) z_on_ ^= 1;
}

// Opposite joystick contacts together mean a fault or a bounce: neither direction.
uint8_t OperatorPanel::state() {
  uint8_t bits = stable_;
  const uint8_t horizontal = hal::kJoyLeft | hal::kJoyRight;
  const uint8_t vertical = hal::kJoyDown | hal::kJoyUp;
  if ((bits & horizontal) == horizontal) bits &= (uint8_t)~horizontal;
  if ((bits & vertical) == vertical) bits &= (uint8_t)~vertical;
  if (z_mode_ == kZToggle) {
    bits &= (uint8_t)~hal::kButtonZ;
    if (z_on_) bits |= hal::kButtonZ;
  }
  return bits;
}

}  // namespace drivers
