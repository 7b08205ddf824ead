// The register-map layer: every special function register access in the port goes through
// Sfr16<address>. On the dsPIC it is the volatile SFR itself; on the host it calls into
// hal/fake/dspic_registers, a 2 KB fake SFR file whose hooks behave like the peripherals.
#ifndef HAL_DSPIC30F6014_SFR_H
#define HAL_DSPIC30F6014_SFR_H

#include <stdint.h>  // uint8_t, uint16_t, uint32_t

#include "hal/dspic30f6014/platform.h"  // DSPIC_TARGET

namespace dspic {

// Mask of one bit.
inline uint16_t bit(uint8_t n) {
  return (uint16_t)(1u << n);
}

#if DSPIC_TARGET

// The free XC16 licence stops at -O1; forcing these one-liners inline keeps each access a
// single instruction there too.
#define DSPIC_INLINE inline __attribute__((always_inline))

// One bit field per bit, so a constant bit compiles to a single BSET/BCLR (atomic against
// interrupts, unlike a load-or-store sequence), as with Microchip's own xxxbits structs.
struct SfrBits {
  uint16_t b0 : 1, b1 : 1, b2 : 1, b3 : 1, b4 : 1, b5 : 1, b6 : 1, b7 : 1;
  uint16_t b8 : 1, b9 : 1, b10 : 1, b11 : 1, b12 : 1, b13 : 1, b14 : 1, b15 : 1;
};

#define DSPIC_BIT_CASE(n) \
  case n:                 \
    r.b##n = value;       \
    break;

// Writes one bit; with a constant bit and value the switch folds to one instruction.
template <uint16_t kAddress>
DSPIC_INLINE void sfr_write_bit(uint8_t n, uint16_t value) {
  volatile SfrBits& r = *reinterpret_cast<volatile SfrBits*>(kAddress);
  // The case-generating macro confuses the formatter's statement layout.
  // clang-format off
  switch (n) {
    DSPIC_BIT_CASE(0) DSPIC_BIT_CASE(1) DSPIC_BIT_CASE(2) DSPIC_BIT_CASE(3)
    DSPIC_BIT_CASE(4) DSPIC_BIT_CASE(5) DSPIC_BIT_CASE(6) DSPIC_BIT_CASE(7)
    DSPIC_BIT_CASE(8) DSPIC_BIT_CASE(9) DSPIC_BIT_CASE(10) DSPIC_BIT_CASE(11)
    DSPIC_BIT_CASE(12) DSPIC_BIT_CASE(13) DSPIC_BIT_CASE(14) DSPIC_BIT_CASE(15)
    default: break;
  }
  // clang-format on
}
#undef DSPIC_BIT_CASE

template <uint16_t kAddress>
struct Sfr16 {
  static const uint16_t address = kAddress;
  static DSPIC_INLINE volatile uint16_t& ref() {
    return *reinterpret_cast<volatile uint16_t*>(kAddress);
  }
  static DSPIC_INLINE uint16_t read() { return ref(); }
  static DSPIC_INLINE void write(uint16_t value) { ref() = value; }
  // Low byte only (byte write to the even address), e.g. LATD<7:0> for the LCD bus.
  static DSPIC_INLINE void write_low_byte(uint8_t value) {
    *reinterpret_cast<volatile uint8_t*>(kAddress) = value;
  }
  template <uint8_t kBit>
  static DSPIC_INLINE void set_bit() {
    static_assert(kBit < 16, "an SFR has 16 bits");
    sfr_write_bit<kAddress>(kBit, 1);
  }
  template <uint8_t kBit>
  static DSPIC_INLINE void clear_bit() {
    static_assert(kBit < 16, "an SFR has 16 bits");
    sfr_write_bit<kAddress>(kBit, 0);
  }
  template <uint8_t kBit>
  static DSPIC_INLINE bool test_bit() {
    return (ref() & (1u << kBit)) != 0;
  }
  // Read-modify-write of several bits: only for registers no interrupt handler writes.
  static DSPIC_INLINE void modify(uint16_t clear_mask, uint16_t set_mask) {
    ref() = (uint16_t)((ref() & (uint16_t)~clear_mask) | set_mask);
  }
};

// Libpic30's calibrated busy wait (declared here: libpic30.h does not compile as C++).
extern "C" void __delay32(unsigned long cycles);

// Busy-waits at least this many instruction cycles (short waits: NOPs, longer: __delay32,
// whose own overhead sets its minimum of about a dozen cycles).
inline void delay_cycles(uint32_t cycles) {
  if (cycles < 16) {
    for (uint8_t i = 0; i < (uint8_t)cycles; ++i) __builtin_nop();
  } else {
    __delay32(cycles);
  }
}

#else  // host: the fake register file (hal/fake/dspic_registers)

namespace host {
uint16_t sfr_read(uint16_t address);
void sfr_write(uint16_t address, uint16_t value);
void sfr_write_low_byte(uint16_t address, uint8_t value);
void sfr_set_bit(uint16_t address, uint8_t n);
void sfr_clear_bit(uint16_t address, uint8_t n);
void delay_cycles(uint32_t cycles);
}  // namespace host

template <uint16_t kAddress>
struct Sfr16 {
  static const uint16_t address = kAddress;
  static uint16_t read() { return host::sfr_read(kAddress); }
  static void write(uint16_t value) { host::sfr_write(kAddress, value); }
  static void write_low_byte(uint8_t value) { host::sfr_write_low_byte(kAddress, value); }
  template <uint8_t kBit>
  static void set_bit() {
    static_assert(kBit < 16, "an SFR has 16 bits");
    host::sfr_set_bit(kAddress, kBit);
  }
  template <uint8_t kBit>
  static void clear_bit() {
    static_assert(kBit < 16, "an SFR has 16 bits");
    host::sfr_clear_bit(kAddress, kBit);
  }
  template <uint8_t kBit>
  static bool test_bit() {
    return (read() & (1u << kBit)) != 0;
  }
  static void modify(uint16_t clear_mask, uint16_t set_mask) {
    write((uint16_t)((read() & (uint16_t)~clear_mask) | set_mask));
  }
};

inline void delay_cycles(uint32_t cycles) {
  host::delay_cycles(cycles);
}

#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_SFR_H
