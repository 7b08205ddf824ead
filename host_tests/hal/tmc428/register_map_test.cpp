// The one register map (tmc428_map.h) against the behavioural model, which decodes
// datagrams with its own code (it is the test oracle): every writable register at the map's
// address stores every bit of the map's fields where the map says, motor by motor.
#include <gtest/gtest.h>

#include <set>     // std::set
#include <string>  // std::string

#include "hal/drivers/tmc428/tmc428_map.h"
#include "hal/drivers/tmc428/tmc428_regs.h"
#include "hal/fake/motion/tmc428_model.h"

namespace {

using namespace drivers::tmc428;

// The map's bits of a register: every field, all ones.
uint32_t field_bits(const RegisterInfo& r) {
  uint32_t bits = 0;
  for (const RegisterField* f = r.fields; f->kind != kFieldEnd; ++f) {
    for (int b = f->lo; b <= f->hi; ++b) bits |= 1UL << b;
  }
  return bits;
}

// Registers whose writes the model stores as written (no side effects on other state, no
// read-only or forced bits).
const std::set<std::string> kPlainMotorRegisters = {
    "x_target", "v_min", "v_max", "a_max", "current_scale", "dividers", "dx_ref_tolerance"};

TEST(Tmc428RegisterMap, ModelStoresEachFieldOfThePlainRegistersWhereTheMapSays) {
  uint8_t count = 0;
  const RegisterInfo* regs = all_registers(&count);
  int checked = 0;
  for (uint8_t i = 0; i < count; ++i) {
    const RegisterInfo& r = regs[i];
    if (kPlainMotorRegisters.count(r.name) == 0) continue;
    const uint32_t bits = field_bits(r);
    for (uint8_t motor = 0; motor < 3; ++motor) {
      fake::Tmc428Model chip;
      chip.transfer32(write_datagram(motor_reg(motor, r.address), bits));
      const int idx = (r.address >> 1) & 0xF;
      EXPECT_EQ(chip.reg(motor, idx), bits) << r.name << " motor " << int(motor);
      for (uint8_t other = 0; other < 3; ++other) {
        if (other != motor) EXPECT_EQ(chip.reg(other, idx), 0u) << r.name;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3 * static_cast<int>(kPlainMotorRegisters.size()));
}

TEST(Tmc428RegisterMap, ModelAgreesOnSmgpAndRefSwitchBits) {
  fake::Tmc428Model chip;
  const RegisterInfo* smgp = find_register(kSmgp);
  ASSERT_NE(smgp, nullptr);
  const uint32_t bits = field_bits(*smgp);
  chip.transfer32(write_datagram(kSmgp, bits));
  EXPECT_EQ(chip.common_reg(15), bits);
  // Reference switches: motor 1's left switch is l1, bit 1 in the map.
  chip.set_switch_positions(0, 0, 1000000);
  const RegisterInfo* sw = find_register(kRefSwitches);
  ASSERT_NE(sw, nullptr);
  uint32_t l1 = 0;
  for (const RegisterField* f = sw->fields; f->kind != kFieldEnd; ++f) {
    if (std::string(f->name) == "l1") l1 = 1UL << f->lo;
  }
  EXPECT_EQ(datagram_data(chip.transfer32(read_datagram(kRefSwitches))) & l1, l1);
}

TEST(Tmc428RegisterMap, NamesAreTheBenchNames) {
  char name[kRegisterNameBytes];
  register_name(motor_reg(1, kVTarget), name);
  EXPECT_STREQ(name, "M2.v_target");
  register_name(kSmgp | kReadBit, name);
  EXPECT_STREQ(name, "SMGP");
  register_name(kRamDriverChain + 10, name);
  EXPECT_STREQ(name, "drv_chain[5]");
  register_name(kRamSineTable + 6, name);
  EXPECT_STREQ(name, "ustep_table[3]");
  register_name(0x68, name);
  EXPECT_STREQ(name, "unused_c4");
}

// The driver's data builders and read-back masks take their bits from the map's field
// rows (issue 26): each builder with every argument all ones sets exactly the map's bits
// of its register, and each field's bits only where the map puts them.
const RegisterInfo& reg(uint8_t address) {
  const RegisterInfo* r = find_register(address);
  EXPECT_NE(r, nullptr);
  return *r;
}

uint32_t one_field_bits(const RegisterInfo& r, const char* name) {
  for (const RegisterField* f = r.fields; f->kind != kFieldEnd; ++f) {
    if (std::string(f->name) != name) continue;
    uint32_t bits = 0;
    for (int b = f->lo; b <= f->hi; ++b) bits |= 1UL << b;
    return bits;
  }
  ADD_FAILURE() << "no field " << name << " in " << r.name;
  return 0;
}

TEST(Tmc428RegisterMap, BuildersSetTheMapsFieldBits) {
  EXPECT_EQ(divisors_data(0xFF, 0xFF, 0xFF), field_bits(reg(kDivisors)));
  EXPECT_EQ(divisors_data(0xFF, 0, 0), one_field_bits(reg(kDivisors), "pulse_div"));
  EXPECT_EQ(divisors_data(0, 0xFF, 0), one_field_bits(reg(kDivisors), "ramp_div"));
  EXPECT_EQ(divisors_data(0, 0, 0xFF), one_field_bits(reg(kDivisors), "usrs"));
  EXPECT_EQ(current_scale_data(0xFF, 0xFF, 0xFF, 0xFFFF), field_bits(reg(kCurrentScale)));
  EXPECT_EQ(current_scale_data(0xFF, 0, 0, 0), one_field_bits(reg(kCurrentScale), "is_agtat"));
  EXPECT_EQ(current_scale_data(0, 0xFF, 0, 0), one_field_bits(reg(kCurrentScale), "is_aleat"));
  EXPECT_EQ(current_scale_data(0, 0, 0xFF, 0), one_field_bits(reg(kCurrentScale), "is_v0"));
  EXPECT_EQ(current_scale_data(0, 0, 0, 0xFFFF), one_field_bits(reg(kCurrentScale), "a_threshold"));
  EXPECT_EQ(pmul_pdiv_data(0xFF, 0xFF), field_bits(reg(kPmulPdiv)));
  EXPECT_EQ(pmul_pdiv_data(0, 0xFF), one_field_bits(reg(kPmulPdiv), "pdiv") | 0x8000u);
}

TEST(Tmc428RegisterMap, ReadBackMasksAndFlagBitsAreTheMaps) {
  EXPECT_EQ(kAllFields_kDivisors, field_bits(reg(kDivisors)));
  EXPECT_EQ(kAllFields_kCurrentScale, field_bits(reg(kCurrentScale)));
  EXPECT_EQ(kAllFields_kPmulPdiv, field_bits(reg(kPmulPdiv)));
  EXPECT_EQ(kAllFields_kVMax, field_bits(reg(kVMax)));
  EXPECT_EQ(kAllFields_kDxRefTolerance, field_bits(reg(kDxRefTolerance)));
  EXPECT_EQ(kAllFields_kSmgp, field_bits(reg(kSmgp)));
  EXPECT_EQ(kSmgpContinuousUpdate, one_field_bits(reg(kSmgp), "cont_update"));
  EXPECT_EQ(kSmgpRefMux, one_field_bits(reg(kSmgp), "refmux"));
  EXPECT_EQ(kSmgpClk2DivShift, 8u);
  EXPECT_EQ(kSmgpClk2DivShift, (uint32_t)__builtin_ctzl(one_field_bits(reg(kSmgp), "clk2_div")));
  const uint32_t ref_conf = one_field_bits(reg(kRefConfRampMode), "ref_conf");
  EXPECT_EQ((uint32_t)(kDisableStopL | kDisableStopR | kSoftStop | kRefRnL), ref_conf);
  EXPECT_EQ(kLatchPending, one_field_bits(reg(kRefConfRampMode), "lp"));
}

}  // namespace
