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

}  // namespace
