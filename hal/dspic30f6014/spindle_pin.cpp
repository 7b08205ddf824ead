// Spindle output on RD11 (pin map in pins.h).
#include "hal/dspic30f6014/spindle_pin.h"

#include "hal/dspic30f6014/pins.h"       // kSpindleBit
#include "hal/dspic30f6014/registers.h"  // LATD

namespace dspic {

void SpindlePin::set_on(bool on) {
  if (on) {
    LATD::set_bit<pins::kSpindleBit>();
  } else {
    LATD::clear_bit<pins::kSpindleBit>();
  }
}

}  // namespace dspic
