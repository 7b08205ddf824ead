// SPI1 master for the TMC428 (Family Reference Manual SPI sec. 20.4; TMC428 data sheet timing).
#include "hal/dspic30f6014/spi1.h"

#include "hal/dspic30f6014/clock.h"      // kFcyHz
#include "hal/dspic30f6014/pins.h"       // kTmcCsBit
#include "hal/dspic30f6014/registers.h"  // SPI1STAT, SPI1CON, SPI1BUF, LATB

namespace dspic {

namespace {
// Primary prescale by PPRE<1:0> (00 = 64:1 ... 11 = 1:1); secondary is 8 - SPRE<2:0>.
const uint8_t kPrimary[4] = {64, 16, 4, 1};
}  // namespace

const uint32_t Spi1::kTimeoutAnswer;

Spi1::Spi1() : spin_limit_(0), timeouts_(0) {}

// Smallest divider (fastest clock) whose exact SCK, Fcy / divider, does not exceed the
// limit; of equal dividers the one with the smaller primary prescale is kept. ceil(Fcy / d)
// <= max_sck exactly when d >= ceil(Fcy / max_sck): one division, not one per setting.
uint16_t Spi1::prescale_bits(uint32_t fcy_hz, uint32_t max_sck_hz) {
  uint32_t least = 0;  // any divider clocks 0 Hz slowly enough
  if (fcy_hz != 0) {
    if (max_sck_hz == 0) return kNoPrescale;
    least = (fcy_hz - 1u) / max_sck_hz + 1u;
  }
  uint16_t best = kNoPrescale;
  uint16_t best_divider = 0xFFFF;
  for (int8_t ppre = 3; ppre >= 0; --ppre) {    // primary 1, 4, 16, 64
    for (int8_t spre = 7; spre >= 0; --spre) {  // secondary 1 .. 8
      const uint16_t divider = (uint16_t)(kPrimary[ppre] * (uint16_t)(8 - spre));
      if (divider == 1) continue;  // 1:1 with 1:1 is not a valid setting
      if (divider < least || divider >= best_divider) continue;
      best_divider = divider;
      best = (uint16_t)(ppre | (spre << 2));
    }
  }
  return best;
}

// Fcy / SCK of a prescale setting: primary (1, 4, 16, 64) times secondary (8 - SPRE).
static uint16_t divider_of(uint16_t bits) {
  return (uint16_t)(kPrimary[bits & 3u] * (uint16_t)(8 - ((bits >> 2) & 7u)));
}

uint32_t Spi1::sck_hz(uint32_t fcy_hz, uint16_t bits) {
  return fcy_hz / divider_of(bits);
}

// MODE16 may only change with SPIEN = 0, so the module is off while configured.
bool Spi1::init(uint32_t max_sck_hz) {
  SPI1STAT::write(0);
  const uint16_t prescale = prescale_bits(kFcyHz, max_sck_hz);
  if (prescale == kNoPrescale) return false;
  SPI1CON::write((uint16_t)(bit(SPI1CONbits::MODE16) | bit(SPI1CONbits::CKP) |
                            bit(SPI1CONbits::MSTEN) | prescale));
  // One word lasts 16 * divider cycles; a poll takes at least one, so this many polls
  // outlast a word, and a dead bus costs about a word time, never a hang.
  spin_limit_ = (uint16_t)(16u * divider_of(prescale));
  timeouts_ = 0;
  SPI1STAT::write(bit(SPI1STATbits::SPIEN));
  return true;
}

// One word: write SPI1BUF, wait for SPIRBF, read SPI1BUF (which clears SPIRBF).
bool Spi1::exchange(uint16_t out, uint16_t* in) {
  SPI1BUF::write(out);
  for (uint16_t i = 0; i < spin_limit_; ++i) {
    if (SPI1STAT::test_bit<SPI1STATbits::SPIRBF>()) {
      *in = SPI1BUF::read();
      return true;
    }
  }
  timeouts_ = (uint16_t)(timeouts_ + 1);
  return false;
}

// The TMC428 takes the 32 bits shifted while nSCS_C is low and answers the same way.
uint32_t Spi1::transfer32(uint32_t mosi) {
  if (SPI1STAT::test_bit<SPI1STATbits::SPIRBF>()) (void)SPI1BUF::read();  // stale word
  if (SPI1STAT::test_bit<SPI1STATbits::SPIROV>()) SPI1STAT::clear_bit<SPI1STATbits::SPIROV>();
  uint16_t high = 0;
  uint16_t low = 0;
  LATB::clear_bit<pins::kTmcCsBit>();
  delay_cycles(kChipSelectCycles);
  const bool ok = exchange((uint16_t)(mosi >> 16), &high) && exchange((uint16_t)mosi, &low);
  delay_cycles(kChipSelectCycles);
  LATB::set_bit<pins::kTmcCsBit>();
  delay_cycles(kChipSelectCycles);  // nSCS_C high time before the next datagram
  if (!ok) return kTimeoutAnswer;
  return ((uint32_t)high << 16) | low;
}

}  // namespace dspic
