// Busy waits at the board's instruction clock.
#include "hal/dspic30f6014/clock.h"

#include "hal/dspic30f6014/sfr.h"  // delay_cycles

namespace dspic {

void delay_us(uint16_t us) {
  delay_cycles((uint32_t)us * kCyclesPerUs);
}

}  // namespace dspic
