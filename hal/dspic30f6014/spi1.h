// SPI1 as master to the TMC428: SPI mode 3 (CKP = 1 clock idles high, CKE = 0 output changes
// on the idle-to-active edge, SMP = 0 sample mid-bit), 16-bit words, two words per 32-bit
// datagram (MSB word first), chip select by GPIO (RB2). Implements hal::SpiMaster.
#ifndef HAL_DSPIC30F6014_SPI1_H
#define HAL_DSPIC30F6014_SPI1_H

#include <stdint.h>  // uint16_t, uint32_t

#include "hal/interfaces/spi_master.h"  // hal::SpiMaster

namespace dspic {

#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
// A concrete port object, never deleted through a base pointer.
class Spi1 : public hal::SpiMaster {
 public:
  enum {
    kNoPrescale = 0xFFFF,  // prescale_bits(): no divider reaches the requested clock
    // nSCS_C setup, hold and high time are 3 TMC428 clocks (300 ns at 10 MHz = 6 Tcy);
    // 8 Tcy (400 ns) each leaves margin.
    kChipSelectCycles = 8
  };
  // What transfer32() returns when the bus did not complete a word (MISO floating high).
  static const uint32_t kTimeoutAnswer = 0xFFFFFFFFUL;

  Spi1();
  // PPRE<1:0> | SPRE<2:0> << 2 for the fastest SCK <= max_sck_hz, F_SCK = Fcy / (primary *
  // secondary) [FRM sec. 20.4]; kNoPrescale if even 64 * 8 is too fast. 1:1 with 1:1 is never
  // chosen.
  static uint16_t prescale_bits(uint32_t fcy_hz, uint32_t max_sck_hz);
  // SCK those bits give.
  static uint32_t sck_hz(uint32_t fcy_hz, uint16_t prescale_bits);
  // Master, mode 3, 16-bit words, fastest SCK <= max_sck_hz; false (SPI left off) if
  // impossible. The chip-select pin must already be an output driven high (init_ports()).
  bool init(uint32_t max_sck_hz);

  // hal::SpiMaster: CS low, high word, low word, CS high. On a stuck bus: kTimeoutAnswer.
  virtual uint32_t transfer32(uint32_t mosi);

  // Words that never completed since init.
  uint16_t timeouts() const { return timeouts_; }

 private:
  bool exchange(uint16_t out, uint16_t* in);

  uint16_t spin_limit_;  // polls of SPIRBF before a word counts as lost
  uint16_t timeouts_;
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_SPI1_H
