// The board's clock: 10 MHz crystal, XT with PLL x8 (set by the configuration bits in
// config_bits.c), Fosc 80 MHz, Fcy = Fosc / 4 = 20 MHz (data sheet DS70117, oscillator).
#ifndef HAL_DSPIC30F6014_CLOCK_H
#define HAL_DSPIC30F6014_CLOCK_H

#include <stdint.h>  // uint32_t

namespace dspic {

static const uint32_t kCrystalHz = 10000000UL;
static const uint32_t kPllMultiplier = 8;
static const uint32_t kFcyHz = kCrystalHz * kPllMultiplier / 4;  // 20 MIPS, Tcy = 50 ns
static const uint32_t kCyclesPerUs = kFcyHz / 1000000UL;         // 20

// Busy-waits at least us microseconds (ok from any context; used for LCD timing).
void delay_us(uint16_t us);

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_CLOCK_H
