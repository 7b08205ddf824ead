// Host-only panel pin source: a test sets which contacts are closed, or scripts a sequence
// of raw samples (bounce), one per read.
#ifndef HAL_FAKE_PANEL_FAKE_PANEL_PINS_H
#define HAL_FAKE_PANEL_FAKE_PANEL_PINS_H

#include <stdint.h>

#include <deque>

#include "hal/interfaces/panel_pins.h"

namespace fake {

class PanelPins : public hal::PanelPins {
 public:
  PanelPins() : level_(0), reads_(0) {}
  // hal::PanelPins: the next scripted sample if any, else the steady level.
  uint8_t read_raw() override {
    ++reads_;
    if (!script_.empty()) {
      const uint8_t sample = script_.front();
      script_.pop_front();
      return sample;
    }
    return level_;
  }
  // Steady contact state (hal::InputBits, 1 = closed).
  void set(uint8_t bits) { level_ = bits; }
  // Samples returned one per read before the steady level resumes.
  void script(std::initializer_list<uint8_t> samples) {
    script_.insert(script_.end(), samples.begin(), samples.end());
  }
  int reads() const { return reads_; }

 private:
  uint8_t level_;
  int reads_;
  std::deque<uint8_t> script_;
};

}  // namespace fake

#endif  // HAL_FAKE_PANEL_FAKE_PANEL_PINS_H
