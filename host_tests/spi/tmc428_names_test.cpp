// TMC428 register names, fields and status bits (values from shared/reference/tmc428.md).
#include <gtest/gtest.h>

#include "host/spi/tmc428_names.h"

using namespace host::spi;

namespace {

int64_t field(const Tmc428Datagram& d, const std::string& name) {
  for (const Field& f : d.fields)
    if (f.name == name) return f.value;
  ADD_FAILURE() << "no field " << name;
  return -999999;
}

TEST(Tmc428Names, AddressByteGivesRegisterAndMotor) {
  EXPECT_EQ(tmc428_register_name(0x1A), "M1.dx_ref_tolerance");  // datasheet example 0x1A000123
  EXPECT_EQ(tmc428_register_name(0x08), "M1.v_target");
  EXPECT_EQ(tmc428_register_name(0x22), "M2.x_actual");
  EXPECT_EQ(tmc428_register_name(0x54), "M3.ref_conf_mode");
  EXPECT_EQ(tmc428_register_name(0x7E), "SMGP");
  EXPECT_EQ(tmc428_register_name(0x60), "datagram_low_word");
  EXPECT_EQ(tmc428_register_name(0x8A), "drv_chain[5]");
  EXPECT_EQ(tmc428_register_name(0xFE), "ustep_table[31]");
}

TEST(Tmc428Names, ReadBitIsTheLowestAddressBit) {
  Tmc428Datagram d = decode_tmc428(0x03000000, true, 0x15FFFFFF);
  EXPECT_TRUE(d.read);
  EXPECT_EQ(d.reg, "M1.x_actual");
  EXPECT_TRUE(d.fields_from_miso);
  EXPECT_EQ(field(d, "x"), -1);  // 24-bit signed
}

TEST(Tmc428Names, VTargetIsSigned12Bit) {
  EXPECT_EQ(field(decode_tmc428(0x08000FFF, false, 0), "v"), -1);
  EXPECT_EQ(field(decode_tmc428(0x08000800, false, 0), "v"), -2048);
  EXPECT_EQ(field(decode_tmc428(0x080007FF, false, 0), "v"), 2047);
}

TEST(Tmc428Names, SmgpFieldsOfTheBoardValue) {
  Tmc428Datagram d = decode_tmc428(0x7E010702, false, 0);
  EXPECT_EQ(field(d, "lsmd"), 2);
  EXPECT_EQ(field(d, "clk2_div"), 7);
  EXPECT_EQ(field(d, "cont_update"), 1);
  EXPECT_EQ(field(d, "refmux"), 0);
}

TEST(Tmc428Names, RampModeAndRefConf) {
  Tmc428Datagram d = decode_tmc428(0x14000302, false, 0);  // velocity mode, no stops
  ASSERT_FALSE(d.fields.empty());
  EXPECT_EQ(d.fields[0].text, "VELOCITY");
  EXPECT_EQ(field(d, "ref_conf"), 3);
}

TEST(Tmc428Names, DriverChainEntriesAreNamed) {
  Tmc428Datagram d = decode_tmc428(0x8A002E0A, false, 0);
  ASSERT_EQ(d.fields.size(), 2u);
  EXPECT_EQ(d.fields[0].text, "DAC_B2");    // even entry 0x0A
  EXPECT_EQ(d.fields[1].text, "PH_B+NxM");  // odd entry 0x2E
}

TEST(Tmc428Names, StatusBitsInDatasheetOrder) {
  EXPECT_EQ(tmc428_status_bits(0x15), (std::vector<std::string>{"xEQt3", "xEQt2", "xEQt1"}));
  EXPECT_EQ(tmc428_status_bits(0xC2), (std::vector<std::string>{"INT", "CDGW", "RS1"}));
}

}  // namespace
