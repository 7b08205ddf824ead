// The probe input on RA12 (INT1), active low: the clip on the copper is pulled up, the tool
// (at GND) touching the copper pulls it low. INT1 (falling edge) latches a touch shorter than
// the 1 ms tick; the application debounces. Implements hal::ProbeInput.
#ifndef HAL_DSPIC30F6014_PROBE_PIN_H
#define HAL_DSPIC30F6014_PROBE_PIN_H

#include "hal/interfaces/probe_input.h"  // hal::ProbeInput

namespace dspic {

#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
// A concrete port object, never deleted through a base pointer.
class ProbePin : public hal::ProbeInput {
 public:
  ProbePin() : touched_(false) {}
  // RA12 input, INT1 on the falling edge at kProbePriority, flag cleared, then enabled.
  void init();
  // The pin reads low now, or INT1 saw a falling edge since the last call. Tick only.
  virtual bool closed();
  // From the INT1 vector: remembers the edge and acknowledges it.
  void on_int1_interrupt();

 private:
  volatile bool touched_;
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_PROBE_PIN_H
