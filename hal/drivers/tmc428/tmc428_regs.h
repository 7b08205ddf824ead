// TMC428 register map and 32-bit SPI datagram encode/decode (datasheet names kept).
// Sources: [428DS] Trinamic TMC428 data sheet v2.x, [429DS] TMC429 datasheet rev 2.06
// (the 100 % compatible successor, same map); see docs/tmc428.md.
#ifndef HAL_DRIVERS_TMC428_TMC428_REGS_H
#define HAL_DRIVERS_TMC428_TMC428_REGS_H

#include <stdint.h>  // uint32_t, int32_t

#include "hal/drivers/tmc428/tmc428_map.h"  // TMC428_REGISTER_MAP

namespace drivers {
namespace tmc428 {

// ---- Datagram layout, [428DS] §6.4 -------------------------------------------------------
// MOSI: bit 31 RRS (0 register, 1 RAM), 30..25 ADDRESS, 24 RW (1 read), 23..0 DATA.
// For registers ADDRESS = SMDA(2 bits) : IDX(4 bits); the first byte is
// RRS<<7 | SMDA<<5 | IDX<<1 | RW. The addresses below are that first byte, write form.
enum : uint8_t { kReadBit = 0x01, kRamBit = 0x80 };

// Register addresses (first datagram byte, write form) from the register map
// (tmc428_map.h): per-motor registers for motor 0 (motor_reg() adds the motor), then the
// common ones (SMDA = 11): kXTarget 0x00 ... kXLatched 0x1C, kDatagramLowWord 0x60 ...
// kSmgp 0x7E.
#define TMC428_ADDRESS_REG(block, idx, constant, text) \
  constant = (uint8_t)(TMC428_BLOCK_BASE_##block | ((idx) << 1)),
#define TMC428_ADDRESS_SKIP(...)
enum : uint8_t {
  TMC428_REGISTER_MAP(TMC428_ADDRESS_REG, TMC428_ADDRESS_SKIP, TMC428_ADDRESS_SKIP) kUstepCount429 =
      0x1E  // IDX 15: TMC429 only; a TMC428 reads 0 (not in the map)
};
#undef TMC428_ADDRESS_REG
#undef TMC428_ADDRESS_SKIP

// RAM, [428DS] §10: two 6-bit entries per datagram (DATA 13..8 odd, 5..0 even entry).
enum : uint8_t {
  kRamDriverChain = 0x80,  // 0x80..0xBE: 32 datagrams, driver chain configuration
  kRamSineTable = 0xC0,    // 0xC0..0xFE: 32 datagrams, quarter sine wave
  kRamPairs = 32           // datagrams per table
};

// Status byte (MISO bits 31..24), [428DS] §6.4.
enum : uint8_t {
  kStatusXEqt1 = 0x01,
  kStatusRs1 = 0x02,
  kStatusXEqt2 = 0x04,
  kStatusRs2 = 0x08,
  kStatusXEqt3 = 0x10,
  kStatusRs3 = 0x20,
  kStatusCdgw = 0x40,
  kStatusInt = 0x80
};

// ramp_mode values, [428DS] Tab. 8-3.
enum : uint8_t { kRampMode = 0, kSoftMode = 1, kVelocityMode = 2, kHoldMode = 3 };

// ---- Register fields, from the map's FIELD rows (tmc428_map.h): their bits are written
// there only. kField_<register>_<field> = lowest bit | width << 5, e.g.
// kField_kDivisors_pulse_div; kAllFields_<register> = the mask of all its fields.
#define TMC428_FIELD_POSITION(constant, name, hi, lo, kind) \
  kField_##constant##_##name = (lo) | (((hi) - (lo) + 1) << 5),
#define TMC428_FIELD_SKIP(...)
enum FieldPosition {
  TMC428_REGISTER_MAP(TMC428_FIELD_SKIP, TMC428_FIELD_POSITION, TMC428_FIELD_SKIP)
      kFieldPositionNone = 0
};
#undef TMC428_FIELD_POSITION

// Lowest bit, width and in-place mask of a field position (constant expressions).
#define TMC428_FIELD_LO(position) ((position)&31)
#define TMC428_FIELD_WIDTH(position) ((position) >> 5)
#define TMC428_FIELD_MASK(position) \
  ((((uint32_t)1 << TMC428_FIELD_WIDTH(position)) - 1) << TMC428_FIELD_LO(position))

#define TMC428_ALL_FIELDS_REG(block, idx, constant, text) kAllFields_##constant = 0
#define TMC428_ALL_FIELDS_FIELD(constant, name, hi, lo, kind) \
  | TMC428_FIELD_MASK(kField_##constant##_##name)
#define TMC428_ALL_FIELDS_END(constant) ,
enum : uint32_t {
  TMC428_REGISTER_MAP(TMC428_ALL_FIELDS_REG, TMC428_ALL_FIELDS_FIELD, TMC428_ALL_FIELDS_END)
      kAllFieldsNone = 0
};
#undef TMC428_ALL_FIELDS_REG
#undef TMC428_ALL_FIELDS_FIELD
#undef TMC428_ALL_FIELDS_END
#undef TMC428_FIELD_SKIP

// A value placed in its field (bits beyond the field's width dropped).
inline uint32_t field_value(uint16_t position, uint32_t value) {
  return (value << TMC428_FIELD_LO(position)) & TMC428_FIELD_MASK(position);
}

// ref_conf bits as they sit in the IDX 10 register, [428DS] Tab. 8-4 ([429DS] §8.1.11.2):
// ref_conf bit 0..3 and lp.
enum : uint32_t {
  kDisableStopL = (uint32_t)1 << TMC428_FIELD_LO(kField_kRefConfRampMode_ref_conf),
  kDisableStopR = kDisableStopL << 1,
  kSoftStop = kDisableStopL << 2,
  kRefRnL = kDisableStopL << 3,
  kLatchPending = TMC428_FIELD_MASK(kField_kRefConfRampMode_lp)  // RO
};

// interrupt_flags / interrupt_mask bits, [428DS] Tab. 8-6.
enum : uint8_t {
  kIntPosEnd = 0x01,
  kIntRefWrong = 0x02,
  kIntRefMiss = 0x04,
  kIntStop = 0x08,
  kIntStopLeftLow = 0x10,
  kIntStopRightLow = 0x20,
  kIntStopLeftHigh = 0x40,
  kIntStopRightHigh = 0x80
};

// SMGP fields, [429DS] §8.2.5 / [428DS] §9.7.
enum : uint32_t {
  kSmgpLsmdMask = TMC428_FIELD_MASK(kField_kSmgp_lsmd),
  kSmgpPolarityNscsS = TMC428_FIELD_MASK(kField_kSmgp_pol_nscs_s),
  kSmgpPolaritySckS = TMC428_FIELD_MASK(kField_kSmgp_pol_sck_s),
  kSmgpPolarityPhAb = TMC428_FIELD_MASK(kField_kSmgp_pol_ph_ab),
  kSmgpPolarityFdAb = TMC428_FIELD_MASK(kField_kSmgp_pol_fd_ab),
  kSmgpPolarityDacAb = TMC428_FIELD_MASK(kField_kSmgp_pol_dac_ab),
  kSmgpCsComInd = TMC428_FIELD_MASK(kField_kSmgp_cs_comind),
  kSmgpClk2DivShift = TMC428_FIELD_LO(kField_kSmgp_clk2_div),
  kSmgpContinuousUpdate = TMC428_FIELD_MASK(kField_kSmgp_cont_update),
  kSmgpRefMux = TMC428_FIELD_MASK(kField_kSmgp_refmux),
  kSmgpMot1r = TMC428_FIELD_MASK(kField_kSmgp_mot1r)
};

// Driver-chain RAM primary signal codes, [428DS] Tab. 11-1.
enum : uint8_t {
  kSigDacA0 = 0x00,  // DAC_A bit n = 0x00 + n
  kSigPhA = 0x06,
  kSigFdA = 0x07,
  kSigDacB0 = 0x08,  // DAC_B bit n = 0x08 + n
  kSigPhB = 0x0E,
  kSigFdB = 0x0F,
  kSigZero = 0x10,
  kSigOne = 0x11,
  kSigDirection = 0x12,
  kSigStep = 0x13,
  kSigNxM = 0x20  // added to the last signal of each motor
};

// First byte of a per-motor register (motor 0..2 = SMDA 00..10).
inline uint8_t motor_reg(uint8_t motor, uint8_t reg) {
  return (uint8_t)((motor << 5) | reg);
}

// A write datagram: address byte in bits 31..24, data in 23..0.
inline uint32_t write_datagram(uint8_t address, uint32_t data) {
  return ((uint32_t)(address & 0xFE) << 24) | (data & 0xFFFFFFUL);
}

// A read datagram (RW = 1, DATA 0).
inline uint32_t read_datagram(uint8_t address) {
  return ((uint32_t)(address | kReadBit) << 24);
}

// Fields of a MOSI datagram.
inline bool datagram_is_read(uint32_t mosi) {
  return (mosi & 0x01000000UL) != 0;
}
inline bool datagram_is_ram(uint32_t mosi) {
  return (mosi & 0x80000000UL) != 0;
}
inline uint32_t datagram_data(uint32_t word) {
  return word & 0xFFFFFFUL;
}

// Status byte of a MISO answer.
inline uint8_t answer_status(uint32_t miso) {
  return (uint8_t)(miso >> 24);
}

// Sign-extends the low `bits` bits of a register value.
inline int32_t sign_extend(uint32_t value, uint8_t bits) {
  const uint32_t sign = (uint32_t)1 << (bits - 1);
  const uint32_t mask = (sign << 1) - 1;
  value &= mask;
  return (value & sign) ? (int32_t)(value | ~mask) : (int32_t)value;
}

// Register data words built from their fields (positions from the map).
inline uint32_t divisors_data(uint8_t pulse_div, uint8_t ramp_div, uint8_t usrs) {
  return field_value(kField_kDivisors_pulse_div, pulse_div) |
         field_value(kField_kDivisors_ramp_div, ramp_div) |
         field_value(kField_kDivisors_usrs, usrs);
}
inline uint32_t current_scale_data(uint8_t is_agtat, uint8_t is_aleat, uint8_t is_v0,
                                   uint16_t a_threshold) {
  return field_value(kField_kCurrentScale_is_agtat, is_agtat) |
         field_value(kField_kCurrentScale_is_aleat, is_aleat) |
         field_value(kField_kCurrentScale_is_v0, is_v0) |
         field_value(kField_kCurrentScale_a_threshold, a_threshold);
}
// pmul is 128..255: its bit 7 (register bit 15) is forced to 1 ([428DS] §8.11).
inline uint32_t pmul_pdiv_data(uint8_t pmul, uint8_t pdiv) {
  return field_value(kField_kPmulPdiv_pmul, (uint32_t)pmul | 0x80) |
         field_value(kField_kPmulPdiv_pdiv, pdiv);
}
// RAM is not a register of the map: two 6-bit entries, [428DS] §10.
inline uint32_t ram_pair_data(uint8_t even_entry, uint8_t odd_entry) {
  return ((uint32_t)(odd_entry & 0x3F) << 8) | (even_entry & 0x3F);
}

}  // namespace tmc428
}  // namespace drivers

#endif  // HAL_DRIVERS_TMC428_TMC428_REGS_H
