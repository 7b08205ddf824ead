// TMC428 datagram encoding/decoding against the data sheet's examples.
#include <gtest/gtest.h>

#include "hal/drivers/tmc428/tmc428_regs.h"

namespace {

using namespace drivers::tmc428;

TEST(Tmc428Datagram, DataSheetWriteExampleEncodes) {
  // [428DS] §6.5: write 0x000123 to ADDRESS %001101 (SMDA 00, IDX 13) -> 0x1A000123.
  EXPECT_EQ(write_datagram(motor_reg(0, kDxRefTolerance), 0x000123), 0x1A000123u);
}

TEST(Tmc428Datagram, ReadSetsRwAndSendsZeroData) {
  EXPECT_EQ(read_datagram(motor_reg(0, kDxRefTolerance)), 0x1B000000u);
  EXPECT_TRUE(datagram_is_read(0x1B000000u));
  EXPECT_FALSE(datagram_is_read(0x1A000123u));
}

TEST(Tmc428Datagram, MotorBlocksAre32AddressBytesApart) {
  EXPECT_EQ(motor_reg(0, kXActual), 0x02);
  EXPECT_EQ(motor_reg(1, kXActual), 0x22);
  EXPECT_EQ(motor_reg(2, kXActual), 0x42);
}

TEST(Tmc428Datagram, VelocityModeNoStopsExampleEncodes) {
  // tmc428.md §3: "motor0 velocity mode, no stops" = 0x14 00 03 02.
  EXPECT_EQ(
      write_datagram(motor_reg(0, kRefConfRampMode), kDisableStopL | kDisableStopR | kVelocityMode),
      0x14000302u);
}

TEST(Tmc428Datagram, WriteMasksDataTo24Bits) {
  EXPECT_EQ(write_datagram(kSmgp, 0xFF110702u), 0x7E110702u);
}

TEST(Tmc428Datagram, RamPairPutsTheOddEntryInBits13To8) {
  // [429DS] §11.4.2 first chain datagram: entries 0x10 (even) and 0x05 (odd) -> 80000510.
  EXPECT_EQ(write_datagram(kRamDriverChain, ram_pair_data(0x10, 0x05)), 0x80000510u);
  EXPECT_TRUE(datagram_is_ram(0x80000510u));
}

TEST(Tmc428Datagram, PmulPdivExampleEncodes) {
  // tmc428.md §4 worked example: p_mul 237 (0xED), pdiv 2 -> 0x1200ED02.
  EXPECT_EQ(write_datagram(motor_reg(0, kPmulPdiv), pmul_pdiv_data(237, 2)), 0x1200ED02u);
  // Bit 15 is forced to 1: pmul 109 (237 - 128) encodes the same.
  EXPECT_EQ(pmul_pdiv_data(109, 2), 0xED02u);
}

TEST(Tmc428Datagram, StatusBitsSitInTheTopByte) {
  // INT 0x80, CDGW 0x40, RS3 0x20, xEQt3 0x10, RS2 0x08, xEQt2 0x04, RS1 0x02, xEQt1 0x01.
  EXPECT_EQ(answer_status(0x15000A5Au), kStatusXEqt1 | kStatusXEqt2 | kStatusXEqt3);
  EXPECT_EQ(answer_status(0xC0000000u), kStatusInt | kStatusCdgw);
  EXPECT_EQ(datagram_data(0x15000A5Au), 0x000A5Au);
}

TEST(Tmc428Datagram, SignExtendsNarrowRegisters) {
  EXPECT_EQ(sign_extend(0xFFF, 12), -1);
  EXPECT_EQ(sign_extend(0x800, 12), -2048);
  EXPECT_EQ(sign_extend(0x7FF, 12), 2047);
  EXPECT_EQ(sign_extend(0x800000, 24), -8388608);
  EXPECT_EQ(sign_extend(0x7FFFFF, 24), 8388607);
}

TEST(Tmc428Datagram, FieldPackersPlaceFieldsAtDataSheetBits) {
  // pulse_div 15..12, ramp_div 11..8, usrs 2..0.
  EXPECT_EQ(divisors_data(2, 5, 4), 0x2504u);
  // is_agtat 22..20, is_aleat 18..16, is_v0 14..12, a_threshold 10..0.
  EXPECT_EQ(current_scale_data(1, 2, 3, 0x7FF), 0x1237FFu);
}

}  // namespace
