// drivers::Tmc428::init against the behavioural model: configured state and fault codes.
#include <gtest/gtest.h>

#include "firmware/config/machine_config.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/fake/motion/tmc428_model.h"
#include "hal/fake/spi/recording_spi.h"

namespace {

using drivers::Tmc428;
using drivers::Tmc428InitResult;

// Passes datagrams to the model, optionally corrupting answers (fault injection).
class FaultyWire : public fake::SpiDevice {
 public:
  explicit FaultyWire(fake::Tmc428Model& chip) : chip_(chip) {}
  uint32_t transfer32(uint32_t mosi) override {
    uint32_t miso = chip_.transfer32(mosi);
    if (corrupt_ && (mosi >> 24) == corrupt_read_of_) miso ^= 0x000001;
    return miso | force_status_;
  }
  uint64_t now_ns() const override { return chip_.now_ns(); }
  void advance_ns(uint64_t ns) override { chip_.advance_ns(ns); }
  bool corrupt_ = false;
  uint8_t corrupt_read_of_ = 0;  // flips data bit 0 in reads of this address byte
  uint32_t force_status_ = 0;    // OR'd into every answer

 private:
  fake::Tmc428Model& chip_;
};

struct Bench {
  config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  FaultyWire wire{chip};
  fake::RecordingSpi spi{wire, 1250000};
  Tmc428 driver{spi, cfg};
};

TEST(Tmc428Init, SucceedsAgainstTheModel) {
  Bench b;
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  EXPECT_TRUE(b.driver.ready());
}

TEST(Tmc428Init, LeavesTheChipInVelocityModeWithSwitchStopsAndMultiplexedSwitches) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  // SMGP: LSMD 2, clk2_div 7, continuous_update, refmux ([428DS] §9.7).
  EXPECT_EQ(b.chip.common_reg(15), 0x110702u);
  for (int m = 0; m < 3; ++m) {
    SCOPED_TRACE(m);
    EXPECT_EQ(b.chip.reg(m, 10), 0x000002u);   // ramp_mode VELOCITY, ref_conf 0 (stops on)
    EXPECT_EQ(b.chip.reg(m, 2), 1u);           // v_min
    EXPECT_EQ(b.chip.reg(m, 4), 0u);           // v_target
    EXPECT_EQ(b.chip.reg(m, 11) >> 8, 0x08u);  // INT_STOP unmasked
  }
}

TEST(Tmc428Init, WritesTheReferenceMachinesRatesToEachMotor) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  // X/Y: 25 mm/s * 2560 usteps/mm = 64000 usteps/s -> pulse_div 2 (max 78.09 kHz),
  // v_max = ceil(64000 * 2^18 / 10 MHz) = 1678; 512000 usteps/s^2 -> ramp_div 5,
  // a_max = round(512000 * 2^36 / 10^14) = 352; 16 usteps -> usrs 4.
  EXPECT_EQ(b.chip.reg(0, 12), 0x2504u);
  EXPECT_EQ(b.chip.reg(0, 3), 1678u);
  EXPECT_EQ(b.chip.reg(0, 6), 352u);
  EXPECT_EQ(b.chip.reg(1, 3), 1678u);
  // Z: 5 mm/s = 12800 usteps/s -> pulse_div 4, v_max = ceil(12800 * 2^20 / 10^7) = 1343.
  EXPECT_EQ(b.chip.reg(2, 12), 0x4504u);
  EXPECT_EQ(b.chip.reg(2, 3), 1343u);
  EXPECT_EQ(b.chip.reg(2, 6), 352u);
  // Current scales: run 0 (100 %) while moving, hold 4/8 at rest.
  EXPECT_EQ(b.chip.reg(0, 8), 0x004000u);
}

TEST(Tmc428Init, LoadsBothRamTables) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  // Driver 1 of the chain: FD_A, DAC_A 5..2, PH_A, FD_B, DAC_B 5..2, PH_B + NxM.
  const uint8_t tmc246[12] = {0x07, 0x05, 0x04, 0x03, 0x02, 0x06,
                              0x0F, 0x0D, 0x0C, 0x0B, 0x0A, 0x2E};
  for (int i = 0; i < 36; ++i) EXPECT_EQ(b.chip.ram_entry(i), tmc246[i % 12]) << i;
  EXPECT_EQ(b.chip.ram_entry(64 + 0), 0);    // sine(0)
  EXPECT_EQ(b.chip.ram_entry(64 + 32), 45);  // int(0.5 + 64 sin(pi/4)) = 45
  EXPECT_EQ(b.chip.ram_entry(64 + 63), 63);
}

TEST(Tmc428Init, ReadsTheThreeTmc246StatusWordsThroughTheChain) {
  Bench b;
  b.chip.set_driver_status(0, 0x100);
  b.chip.set_driver_status(1, 0x3A0);  // LD 1, OTPW
  b.chip.set_driver_status(2, 0xF04);  // LD 7, OLA
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  EXPECT_EQ(b.driver.driver_status(0), 0x100);
  EXPECT_EQ(b.driver.driver_status(1), 0x3A0);
  EXPECT_EQ(b.driver.driver_status(2), 0xF04);
}

TEST(Tmc428Init, ReportsNoResponseWhenMisoIsStuckLow) {
  config::MachineConfig cfg = config::default_machine_config();
  fake::StuckMisoDevice absent(0x00000000);
  fake::RecordingSpi spi(absent, 1250000);
  Tmc428 driver(spi, cfg);
  EXPECT_EQ(driver.init(), Tmc428InitResult::kNoResponse);
  EXPECT_FALSE(driver.ready());
}

TEST(Tmc428Init, ReportsNoResponseWhenMisoIsStuckHigh) {
  config::MachineConfig cfg = config::default_machine_config();
  fake::StuckMisoDevice absent(0xFFFFFFFF);
  fake::RecordingSpi spi(absent, 1250000);
  Tmc428 driver(spi, cfg);
  EXPECT_EQ(driver.init(), Tmc428InitResult::kNoResponse);
}

TEST(Tmc428Init, StopsAtTheProbeWhenTheChipIsAbsent) {
  config::MachineConfig cfg = config::default_machine_config();
  fake::StuckMisoDevice absent(0xFFFFFFFF);
  fake::RecordingSpi spi(absent, 1250000);
  Tmc428 driver(spi, cfg);
  driver.init();
  EXPECT_EQ(spi.records().size(), 5u);  // write, read, write, read, restore: nothing else
}

TEST(Tmc428Init, ReportsRegisterReadbackWhenAProbeReadsBackWrong) {
  Bench b;
  b.wire.corrupt_ = true;
  b.wire.corrupt_read_of_ = 0x1B;  // read of M1 dx_ref_tolerance
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kRegisterReadback);
}

TEST(Tmc428Init, ReportsRamReadbackWhenASineEntryReadsBackWrong) {
  Bench b;
  b.wire.corrupt_ = true;
  b.wire.corrupt_read_of_ = 0xC3;  // read of sine pair 1
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kRamReadback);
}

TEST(Tmc428Init, ReportsRegisterReadbackWhenAMotorRegisterReadsBackWrong) {
  Bench b;
  b.wire.corrupt_ = true;
  b.wire.corrupt_read_of_ = 0x47;  // read of M3 v_max
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kRegisterReadback);
}

TEST(Tmc428Init, ReportsChainTimeoutWhenCdgwNeverClears) {
  Bench b;
  b.wire.force_status_ = 0x40000000;  // CDGW stuck
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kChainTimeout);
}

TEST(Tmc428Init, ReportsChainReadbackWhenTheChainReturnLineIsStuckLow) {
  Bench b;
  b.chip.set_chain_sdi_stuck(0);
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kChainReadback);
}

TEST(Tmc428Init, ReportsChainReadbackWhenOneDriverLacksItsAlwaysOneBit) {
  Bench b;
  b.chip.set_driver_status(1, 0x000);  // unpowered TMC246 shifts zeros
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kChainReadback);
}

TEST(Tmc428Init, ReportsBadConfigForAFeedBeyondTheChip) {
  Bench b;
  b.cfg.axis[config::kAxisY].max_speed_um_per_s = 200000;  // 512000 usteps/s > 312 kHz
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kBadConfig);
  EXPECT_EQ(b.driver.settings_error(), drivers::tmc428::SettingsError::kSpeedTooHigh);
  EXPECT_EQ(b.driver.settings_error_axis(), config::kAxisY);
  EXPECT_TRUE(b.spi.records().empty());
}

TEST(Tmc428Init, ReportsBadConfigForAnSpiClockAboveAnEighthOfTheChipClock) {
  Bench b;
  b.cfg.spi_clock_hz = 2000000;  // > 10 MHz / 8
  EXPECT_EQ(b.driver.init(), Tmc428InitResult::kBadConfig);
  EXPECT_EQ(b.driver.settings_error(), drivers::tmc428::SettingsError::kSpiTooFast);
}

TEST(Tmc428Init, RefusesMotionCommandsAfterAFailedInit) {
  Bench b;
  b.chip.set_chain_sdi_stuck(0);
  ASSERT_NE(b.driver.init(), Tmc428InitResult::kOk);
  const int16_t v[3] = {100, 0, 0};
  EXPECT_FALSE(b.driver.write_velocity_units(v));
}

TEST(Tmc428Init, AWarmRestartStopsAMotorLeftRunning) {
  Bench b;
  // The chip kept running from before a firmware reset: motor 1 at v = 1000.
  b.chip.transfer32(0x18002500u);  // pulse_div 2, ramp_div 5
  b.chip.transfer32(0x060007FFu);  // v_max 2047
  b.chip.transfer32(0x0C000160u);  // a_max 352
  b.chip.transfer32(0x080003E8u);  // v_target 1000
  b.chip.transfer32(0x14000002u);  // VELOCITY_MODE
  b.chip.advance_us(200000);
  ASSERT_EQ(b.chip.v_actual(0), 1000);
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  b.chip.advance_us(200000);
  EXPECT_EQ(b.chip.v_actual(0), 0);
  EXPECT_EQ(b.chip.reg(0, 4), 0u);  // v_target cleared, so nothing restarts
}

// ---- MotionAxes on the model ----------------------------------------------------------

TEST(Tmc428Axes, VelocityWrittenMovesTheAxisAndPositionsReadBack) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  const int16_t v[3] = {1000, -500, 0};
  ASSERT_TRUE(b.driver.write_velocity_units(v));
  b.chip.advance_us(200000);
  b.spi.set_advance_device(false);  // freeze time so the reads see one instant
  int32_t x[3];
  ASSERT_TRUE(b.driver.read_actual_usteps(x));
  EXPECT_GT(x[0], 0);
  EXPECT_LT(x[1], 0);
  EXPECT_EQ(x[2], 0);
  EXPECT_EQ(x[0], b.chip.x_actual(0));
  EXPECT_EQ(x[1], b.chip.x_actual(1));
  int16_t va[3];
  ASSERT_TRUE(b.driver.read_velocity_units(va));
  EXPECT_EQ(va[0], 1000);
  EXPECT_EQ(va[1], -500);
}

TEST(Tmc428Axes, VelocityIsClippedToVMax) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  const int16_t v[3] = {2047, -2047, 2047};
  ASSERT_TRUE(b.driver.write_velocity_units(v));
  EXPECT_EQ(b.chip.reg(0, 4), 1678u);
  EXPECT_EQ(b.chip.reg(1, 4), (uint32_t)(4096 - 1678));
  EXPECT_EQ(b.chip.reg(2, 4), 1343u);
}

TEST(Tmc428Axes, SetActualWritesPositionsIncludingNegativeOnes) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  const int32_t x[3] = {-5, 123456, -8388608};
  ASSERT_TRUE(b.driver.set_actual_usteps(x));
  int32_t got[3];
  ASSERT_TRUE(b.driver.read_actual_usteps(got));
  EXPECT_EQ(got[0], -5);
  EXPECT_EQ(got[1], 123456);
  EXPECT_EQ(got[2], -8388608);
}

TEST(Tmc428Axes, LimitBitsMapLeftAndRightSwitchesPerAxis) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  b.chip.force_switch(0, false, 1);  // X left
  b.chip.force_switch(2, true, 1);   // Z right
  uint8_t bits = 0;
  ASSERT_TRUE(b.driver.read_limits(&bits));
  EXPECT_EQ(bits, hal::kLimitXLeft | hal::kLimitZRight);
}

TEST(Tmc428Axes, ReportsTheConversionsThePathControllerNeeds) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  // One LSB = f_clk / 2^(pulse_div + 16) usteps/s; Q16 -> f_clk / 2^pulse_div.
  EXPECT_EQ(b.driver.usteps_per_s_per_unit_q16(0), 10000000u / 4);
  EXPECT_EQ(b.driver.usteps_per_s_per_unit_q16(2), 10000000u / 16);
  EXPECT_EQ(b.driver.max_velocity_units(0), 1678);
  // a_max / 256 per ramp clock of 10 MHz / 32 / 2^5: 352/256 * 9765.625 / 1000 = 13.4.
  EXPECT_EQ(b.driver.accel_units_per_ms(0), 13);
}

TEST(Tmc428Axes, RereadsDriverStatusAfterInit) {
  Bench b;
  ASSERT_EQ(b.driver.init(), Tmc428InitResult::kOk);
  b.chip.set_driver_status(2, 0x180);  // OT
  EXPECT_TRUE(b.driver.read_driver_status());
  EXPECT_EQ(b.driver.driver_status(2), 0x180);
}

}  // namespace
