// A spindle output for the host: remembers its state and counts the switchings.
#ifndef HAL_FAKE_SPINDLE_FAKE_SPINDLE_H
#define HAL_FAKE_SPINDLE_FAKE_SPINDLE_H

#include "hal/interfaces/spindle.h"  // hal::Spindle

namespace fake {

class FakeSpindle : public hal::Spindle {
 public:
  void set_on(bool on) override {
    if (on != on_) ++switches_;
    on_ = on;
  }
  bool on() const { return on_; }
  // Changes of state (on -> off or off -> on) since construction.
  int switches() const { return switches_; }

 private:
  bool on_ = false;
  int switches_ = 0;
};

}  // namespace fake

#endif  // HAL_FAKE_SPINDLE_FAKE_SPINDLE_H
