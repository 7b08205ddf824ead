// SPI master as the chip drivers see it: one 32-bit full-duplex datagram per chip-select
// period (the TMC428 datagram, [428DS] §6.4), MSB first, SPI mode 3.
#ifndef HAL_INTERFACES_SPI_MASTER_H
#define HAL_INTERFACES_SPI_MASTER_H

#include <stdint.h>  // uint32_t

namespace hal {

class SpiMaster {
 public:
  // Asserts chip select, shifts out the 32 bits of mosi (bit 31 first) while shifting in
  // 32 bits, releases chip select and returns what was shifted in. Blocks until done
  // (one datagram at 1.25 MHz is ~26 us). The implementation keeps chip select high for
  // at least the device's minimum time between datagrams (TMC428: 3 clocks).
  // Called from one context only (the 1 ms control interrupt or init, never both at once).
  virtual uint32_t transfer32(uint32_t mosi) = 0;

 protected:
  ~SpiMaster() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_SPI_MASTER_H
