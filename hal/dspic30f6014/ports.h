// Pin directions and idle levels for the whole board (pin map in pins.h): all analog
// inputs digital, LCD bus and TMC428 chip select as outputs, UART/SPI pins set up.
#ifndef HAL_DSPIC30F6014_PORTS_H
#define HAL_DSPIC30F6014_PORTS_H

namespace dspic {

// Call first in main, before any peripheral init. Outputs get their idle level (LATx)
// before they are made outputs (TRISx), so no pin glitches.
void init_ports();

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_PORTS_H
