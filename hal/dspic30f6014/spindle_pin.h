// The spindle's switch on RD11, active high (drives the spindle relay or SSR input; low at
// reset and after init_ports(), so the spindle stays off until the job turns it on).
// Only the main loop writes LATD (the LCD bus shares it), so read-modify-write is safe.
// Implements hal::Spindle.
#ifndef HAL_DSPIC30F6014_SPINDLE_PIN_H
#define HAL_DSPIC30F6014_SPINDLE_PIN_H

#include "hal/interfaces/spindle.h"  // hal::Spindle

namespace dspic {

#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
// A concrete port object, never deleted through a base pointer.
class SpindlePin : public hal::Spindle {
 public:
  virtual void set_on(bool on);
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_SPINDLE_PIN_H
