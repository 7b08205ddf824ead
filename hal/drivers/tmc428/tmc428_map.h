// The TMC428 register map, written once: every register's block, index, datasheet-style
// name and fields (bits and how to read them). tmc428_regs.h takes the driver's address
// constants from it; the SPI bench (host/spi/tmc428_names) and the datagram descriptions
// of the fakes (hal/fake/motion/tmc428_describe) take names and fields from the table in
// tmc428_map_table.cpp. Source: Trinamic TMC428 data sheet v2.x, Tab. 7-2 (per-motor
// registers) and chapter 9 (common registers); the TMC429 data sheet rev 2.06 has the
// same map.
//
// TMC428_REGISTER_MAP(REG, FIELD, END) calls, per register,
//   REG(block, idx, constant, "name")   block kMotorBlock (SMDA 0..2) or kCommonBlock (3)
//   FIELD(constant, name, hi, lo, kind)  kind: kFieldUnsigned kFieldSigned kFieldHex
//                                        kFieldRampMode (RAMP SOFT VELOCITY HOLD)
//                                        (constant: the REG row's; tmc428_regs.h makes
//                                        kField_<constant>_<name> of it for the builders)
//   END(constant)
#ifndef HAL_DRIVERS_TMC428_TMC428_MAP_H
#define HAL_DRIVERS_TMC428_TMC428_MAP_H

#include <stdint.h>  // uint8_t

// First address byte of each block (SMDA in bits 6..5).
#define TMC428_BLOCK_BASE_kMotorBlock 0x00
#define TMC428_BLOCK_BASE_kCommonBlock 0x60

// clang-format off
#define TMC428_REGISTER_MAP(REG, FIELD, END)                                     \
  REG(kMotorBlock, 0, kXTarget, "x_target")                                      \
    FIELD(kXTarget, x, 23, 0, kFieldSigned)                                      \
  END(kXTarget)                                                                  \
  REG(kMotorBlock, 1, kXActual, "x_actual")                                      \
    FIELD(kXActual, x, 23, 0, kFieldSigned)                                      \
  END(kXActual)                                                                  \
  REG(kMotorBlock, 2, kVMin, "v_min")                                            \
    FIELD(kVMin, v, 10, 0, kFieldUnsigned)                                       \
  END(kVMin)                                                                     \
  REG(kMotorBlock, 3, kVMax, "v_max")                                            \
    FIELD(kVMax, v, 10, 0, kFieldUnsigned)                                       \
  END(kVMax)                                                                     \
  REG(kMotorBlock, 4, kVTarget, "v_target")                                      \
    FIELD(kVTarget, v, 11, 0, kFieldSigned)                                      \
  END(kVTarget)                                                                  \
  REG(kMotorBlock, 5, kVActual, "v_actual")                                      \
    FIELD(kVActual, v, 11, 0, kFieldSigned)                                      \
  END(kVActual)                                                                  \
  REG(kMotorBlock, 6, kAMax, "a_max")                                            \
    FIELD(kAMax, a, 10, 0, kFieldUnsigned)                                       \
  END(kAMax)                                                                     \
  REG(kMotorBlock, 7, kAActual, "a_actual")                                      \
    FIELD(kAActual, a, 11, 0, kFieldSigned)                                      \
  END(kAActual)                                                                  \
  REG(kMotorBlock, 8, kCurrentScale, "current_scale")                            \
    FIELD(kCurrentScale, is_agtat, 22, 20, kFieldUnsigned)                       \
    FIELD(kCurrentScale, is_aleat, 18, 16, kFieldUnsigned)                       \
    FIELD(kCurrentScale, is_v0, 14, 12, kFieldUnsigned)                          \
    FIELD(kCurrentScale, a_threshold, 10, 0, kFieldUnsigned)                     \
  END(kCurrentScale)                                                             \
  REG(kMotorBlock, 9, kPmulPdiv, "pmul_pdiv")                                    \
    FIELD(kPmulPdiv, pmul, 15, 8, kFieldUnsigned)                                \
    FIELD(kPmulPdiv, pdiv, 3, 0, kFieldUnsigned)                                 \
  END(kPmulPdiv)                                                                 \
  REG(kMotorBlock, 10, kRefConfRampMode, "ref_conf_mode")                        \
    FIELD(kRefConfRampMode, ramp_mode, 1, 0, kFieldRampMode)                     \
    FIELD(kRefConfRampMode, ref_conf, 11, 8, kFieldHex)                          \
    FIELD(kRefConfRampMode, lp, 16, 16, kFieldUnsigned)                          \
  END(kRefConfRampMode)                                                          \
  REG(kMotorBlock, 11, kInterrupt, "interrupt")                                  \
    FIELD(kInterrupt, int_mask, 15, 8, kFieldHex)                                \
    FIELD(kInterrupt, int_flags, 7, 0, kFieldHex)                                \
  END(kInterrupt)                                                                \
  REG(kMotorBlock, 12, kDivisors, "dividers")                                    \
    FIELD(kDivisors, pulse_div, 15, 12, kFieldUnsigned)                          \
    FIELD(kDivisors, ramp_div, 11, 8, kFieldUnsigned)                            \
    FIELD(kDivisors, usrs, 2, 0, kFieldUnsigned)                                 \
  END(kDivisors)                                                                 \
  REG(kMotorBlock, 13, kDxRefTolerance, "dx_ref_tolerance")                      \
    FIELD(kDxRefTolerance, dx_ref_tolerance, 11, 0, kFieldUnsigned)              \
  END(kDxRefTolerance)                                                           \
  REG(kMotorBlock, 14, kXLatched, "x_latched")                                   \
    FIELD(kXLatched, x, 23, 0, kFieldSigned)                                     \
  END(kXLatched)                                                                 \
  REG(kCommonBlock, 0, kDatagramLowWord, "datagram_low_word")                    \
    FIELD(kDatagramLowWord, data, 23, 0, kFieldHex)                              \
  END(kDatagramLowWord)                                                          \
  REG(kCommonBlock, 1, kDatagramHighWord, "datagram_high_word")                  \
    FIELD(kDatagramHighWord, data, 23, 0, kFieldHex)                             \
  END(kDatagramHighWord)                                                         \
  REG(kCommonBlock, 2, kCoverPosLen, "cover_pos_len")                            \
    FIELD(kCoverPosLen, cover_pos, 13, 8, kFieldUnsigned)                        \
    FIELD(kCoverPosLen, cover_len, 4, 0, kFieldUnsigned)                         \
    FIELD(kCoverPosLen, cover_waiting, 23, 23, kFieldUnsigned)                   \
  END(kCoverPosLen)                                                              \
  REG(kCommonBlock, 3, kCoverDatagram, "cover_datagram")                         \
    FIELD(kCoverDatagram, cover_datagram, 23, 0, kFieldHex)                      \
  END(kCoverDatagram)                                                            \
  REG(kCommonBlock, 8, kPowerDown, "power_down")                                 \
  END(kPowerDown)                                                                \
  REG(kCommonBlock, 14, kRefSwitches, "ref_switches")                            \
    FIELD(kRefSwitches, r1, 0, 0, kFieldUnsigned)                                \
    FIELD(kRefSwitches, l1, 1, 1, kFieldUnsigned)                                \
    FIELD(kRefSwitches, r2, 2, 2, kFieldUnsigned)                                \
    FIELD(kRefSwitches, l2, 3, 3, kFieldUnsigned)                                \
    FIELD(kRefSwitches, r3, 4, 4, kFieldUnsigned)                                \
    FIELD(kRefSwitches, l3, 5, 5, kFieldUnsigned)                                \
  END(kRefSwitches)                                                              \
  REG(kCommonBlock, 15, kSmgp, "SMGP")                                           \
    FIELD(kSmgp, lsmd, 1, 0, kFieldUnsigned)                                     \
    FIELD(kSmgp, pol_nscs_s, 2, 2, kFieldUnsigned)                               \
    FIELD(kSmgp, pol_sck_s, 3, 3, kFieldUnsigned)                                \
    FIELD(kSmgp, pol_ph_ab, 4, 4, kFieldUnsigned)                                \
    FIELD(kSmgp, pol_fd_ab, 5, 5, kFieldUnsigned)                                \
    FIELD(kSmgp, pol_dac_ab, 6, 6, kFieldUnsigned)                               \
    FIELD(kSmgp, cs_comind, 7, 7, kFieldUnsigned)                                \
    FIELD(kSmgp, clk2_div, 15, 8, kFieldUnsigned)                                \
    FIELD(kSmgp, cont_update, 16, 16, kFieldUnsigned)                            \
    FIELD(kSmgp, refmux, 20, 20, kFieldUnsigned)                                 \
    FIELD(kSmgp, mot1r, 21, 21, kFieldUnsigned)                                  \
  END(kSmgp)
// clang-format on

namespace drivers {
namespace tmc428 {

enum FieldKind { kFieldUnsigned, kFieldSigned, kFieldHex, kFieldRampMode, kFieldEnd };

struct RegisterField {
  const char* name;
  uint8_t hi;
  uint8_t lo;
  uint8_t kind;  // FieldKind; kFieldEnd closes a register's list
};

struct RegisterInfo {
  uint8_t address;  // first datagram byte, write form
  const char* name;
  const RegisterField* fields;  // ends with kind kFieldEnd
};

// The register at a datagram's address byte (RW bit ignored); 0 for RAM and unused
// addresses. The table is in tmc428_map_table.cpp (library hal_tmc428_map, not linked
// into the firmware image).
const RegisterInfo* find_register(uint8_t address_byte);
// The bench's name of a datagram's address byte into out (NUL-terminated, at most
// kRegisterNameBytes with the NUL): "M1.v_target", "SMGP", "drv_chain[5]", "ustep_table[3]",
// "unused_c4", "M2.unused15".
enum { kRegisterNameBytes = 32 };
void register_name(uint8_t address_byte, char* out);
// All registers of the map, in table order; *count gets their number.
const RegisterInfo* all_registers(uint8_t* count);

}  // namespace tmc428
}  // namespace drivers

#endif  // HAL_DRIVERS_TMC428_TMC428_MAP_H
