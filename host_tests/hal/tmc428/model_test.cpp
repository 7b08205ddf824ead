// fake::Tmc428Model: register semantics, velocity-mode ramps and motion, switch stops,
// driver-chain read-back. Raw datagrams, no driver, so the model is pinned on its own.
#include <gtest/gtest.h>

#include "hal/drivers/tmc428/tmc428_regs.h"
#include "hal/fake/motion/tmc428_model.h"

namespace {

using namespace drivers::tmc428;
using fake::Tmc428Model;

uint32_t write(Tmc428Model& c, uint8_t addr, uint32_t data) {
  return c.transfer32(write_datagram(addr, data));
}
uint32_t read(Tmc428Model& c, uint8_t addr) {
  return c.transfer32(read_datagram(addr));
}

// Motor 1 in velocity mode: pulse_div 2, ramp_div 5, a_max 352, v_max 2047.
void velocity_setup(Tmc428Model& c, uint32_t ref_conf = 0) {
  write(c, motor_reg(0, kDivisors), divisors_data(2, 5, 4));
  write(c, motor_reg(0, kVMax), 2047);
  write(c, motor_reg(0, kAMax), 352);
  write(c, motor_reg(0, kInterrupt), (uint32_t)kIntStop << 8);
  write(c, motor_reg(0, kRefConfRampMode), ref_conf | kVelocityMode);
}

// ---- registers ------------------------------------------------------------------------

TEST(Tmc428Model, PowerOnRegistersAreZeroExceptClk2Div15) {
  Tmc428Model c;
  for (int idx = 0; idx < 16; ++idx) {
    if (idx == 9) continue;  // pmul bit 15 reads as the forced 1
    EXPECT_EQ(c.reg(0, idx), 0u) << idx;
  }
  EXPECT_EQ(c.reg(0, 9), 0x8000u);
  EXPECT_EQ(c.common_reg(15), 0x000F00u);  // SMGP clk2_div = 15 ([428DS] §6.1)
}

TEST(Tmc428Model, ReadReturnsTheRegisterInTheSameTransfer) {
  Tmc428Model c;
  write(c, motor_reg(1, kAMax), 1000);
  EXPECT_EQ(datagram_data(read(c, motor_reg(1, kAMax))), 1000u);
}

TEST(Tmc428Model, WriteAnswersTheStatusWithZeroData) {
  Tmc428Model c;
  write(c, motor_reg(0, kXTarget), 0x123);
  // x_target 0x123 != x_actual 0 on motor 1 only: xEQt2, xEQt3 = 0x14.
  EXPECT_EQ(write(c, motor_reg(0, kVMin), 5), 0x14000000u);
}

TEST(Tmc428Model, PowerOnStatusShowsAllMotorsAtTarget) {
  Tmc428Model c;
  // [428DS] §6.5 example state: INT 0, CDGW 0, switches off, xEQt 1,1,1 -> 0x15.
  EXPECT_EQ(read(c, motor_reg(0, kXActual)) >> 24, 0x15u);
}

TEST(Tmc428Model, WritesToReadOnlyRegistersAreIgnored) {
  Tmc428Model c;
  write(c, motor_reg(0, kVActual), 100);  // RO outside HOLD_MODE
  write(c, motor_reg(0, kAActual), 100);
  write(c, kRefSwitches, 0x3F);
  EXPECT_EQ(c.reg(0, 5), 0u);
  EXPECT_EQ(c.reg(0, 7), 0u);
  EXPECT_EQ(c.common_reg(14), 0u);
}

TEST(Tmc428Model, VActualIsWritableInHoldMode) {
  Tmc428Model c;
  write(c, motor_reg(0, kRefConfRampMode), kHoldMode);
  write(c, motor_reg(0, kVActual), 0xF9C);  // -100
  EXPECT_EQ(c.v_actual(0), -100);
}

TEST(Tmc428Model, RegistersKeepOnlyTheirDataSheetWidth) {
  Tmc428Model c;
  write(c, motor_reg(0, kVMax), 0xFFFFFF);
  write(c, motor_reg(0, kVTarget), 0xFFFFFF);
  write(c, motor_reg(0, kDivisors), 0xFFFFFF);
  EXPECT_EQ(c.reg(0, 3), 0x7FFu);    // 11 bits
  EXPECT_EQ(c.reg(0, 4), 0xFFFu);    // 12 bits
  EXPECT_EQ(c.reg(0, 12), 0xFF07u);  // pulse_div, ramp_div, usrs
}

TEST(Tmc428Model, InterruptFlagsClearByWritingOnes) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c);
  c.set_switch_positions(0, -1000000, 10);
  write(c, motor_reg(0, kVTarget), 500);
  c.advance_us(100000);
  ASSERT_EQ(c.reg(0, 11) & kIntStop, kIntStop);
  write(c, motor_reg(0, kInterrupt), ((uint32_t)kIntStop << 8) | kIntStop);
  EXPECT_EQ(c.reg(0, 11) & 0xFF, 0u);
}

TEST(Tmc428Model, RamHoldsTwoEntriesPerDatagram) {
  Tmc428Model c;
  write(c, 0xC2, 0x0503);
  EXPECT_EQ(c.ram_entry(64 + 2), 0x03);
  EXPECT_EQ(c.ram_entry(64 + 3), 0x05);
  EXPECT_EQ(datagram_data(read(c, 0xC2)), 0x0503u);
}

// ---- motion ---------------------------------------------------------------------------

TEST(Tmc428Model, RampReachesTargetAfterTheDataSheetNumberOfRampClocks) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVTarget), 1000);
  // a_max/256 per ramp clock: ceil(1000 * 256 / 352) = 728 ramp clocks of 32 * 2^5 = 1024
  // ticks (102.4 us at 10 MHz) -> 74547.2 us.
  c.advance_us(74547);
  EXPECT_EQ(c.v_actual(0), 999);
  c.advance_us(1);
  EXPECT_EQ(c.v_actual(0), 1000);
}

TEST(Tmc428Model, RampDistanceMatchesTheDataSheetFormula) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(74548);
  // S = 1/2 v^2 / a_max 2^ramp_div / 2^pulse_div / 8 = 0.5e6 / 352 * 32 / 4 / 8 = 1420.5.
  EXPECT_NEAR(c.x_actual(0), 1420.5, 1420.5 * 0.01);
}

TEST(Tmc428Model, ConstantVelocityIntegratesExactly) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(100000);  // ramp done
  const int32_t x0 = c.x_actual(0);
  for (int ms = 0; ms < 1000; ++ms) c.advance_us(1000);
  // R = 10^7 * 1000 / 2^18 = 38146.97 usteps/s; the accumulator keeps the remainder.
  EXPECT_NEAR(c.x_actual(0) - x0, 38147, 1);
}

// The clock ticks are worked out from the current tick by a multiply (the simulator
// advances after every datagram): the same as dividing the whole time, for any steps.
TEST(Tmc428Model, ClockTicksAreTheElapsedNanosecondsOverThePeriod) {
  for (uint32_t f_clk_hz : {10000000u, 16000000u, 8000000u, 1000000000u}) {
    Tmc428Model c(f_clk_hz);
    uint64_t ns = 0;
    uint32_t seed = 1;
    for (int i = 0; i < 20000; ++i) {
      seed = seed * 1103515245u + 12345u;
      // Mostly datagram-sized steps, some a tick or less, now and then past 2^32 ns.
      const uint64_t step = i % 997 == 0 ? (uint64_t{5} << 32) + seed : (seed >> 8) % 60000;
      ns += step;
      c.advance_ns(step);
      const uint64_t ticks = (uint64_t)((unsigned __int128)ns * f_clk_hz / 1000000000u);
      ASSERT_EQ(c.now_ticks(), ticks) << "f_clk " << f_clk_hz << " at " << ns << " ns";
    }
  }
}

// The simulator sends ~7 datagrams a millisecond; a cruising motor far from its switches
// and x_target is integrated when its own position or velocity is read or changed, not
// after each datagram that only reads another motor or the (predictable) status byte.
TEST(Tmc428Model, AMovingMotorIsIntegratedOnlyWhenItIsReadOrChanged) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(100000);
  const int32_t x0 = c.x_actual(0);
  const uint64_t n0 = c.motor_integrations();
  for (int i = 0; i < 7; ++i) {
    read(c, motor_reg(1, kXActual));
    read(c, kRefSwitches);
    write(c, motor_reg(2, kVTarget), 0);
    c.advance_us(26);
  }
  EXPECT_EQ(c.motor_integrations(), n0);
  EXPECT_GT(c.x_actual(0), x0);
  EXPECT_EQ(c.motor_integrations(), n0 + 1);
}

// The driver writes each motor's v_target every tick, mostly unchanged: such a write
// integrates nothing, a new value does.
TEST(Tmc428Model, AVTargetWriteOfTheValueItHoldsIntegratesNothing) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(100000);
  c.x_actual(0);
  const uint64_t n0 = c.motor_integrations();
  for (int i = 0; i < 10; ++i) {
    c.advance_us(1000);
    write(c, motor_reg(0, kVTarget), 1000);
  }
  EXPECT_EQ(c.motor_integrations(), n0);
  write(c, motor_reg(0, kVTarget), 999);
  EXPECT_EQ(c.motor_integrations(), n0 + 1);
  c.advance_us(50000);
  EXPECT_EQ(c.v_actual(0), 999);
}

// Lazy integration changes no answer: a model whose motor is read after every step answers
// every datagram as one left alone, through a ramp, a pass over x_target and a switch stop.
TEST(Tmc428Model, LazyIntegrationAnswersAsIntegratingAfterEveryStep) {
  Tmc428Model eager, lazy;
  for (Tmc428Model* c : {&eager, &lazy}) {
    write(*c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
    velocity_setup(*c);
    write(*c, motor_reg(0, kXTarget), 3000);
    c->set_switch_positions(0, -100000, 9000);
    write(*c, motor_reg(0, kVTarget), 700);
  }
  uint32_t seed = 7;
  for (int i = 0; i < 20000; ++i) {
    seed = seed * 1103515245u + 12345u;
    const uint32_t step_ns = 20000 + (seed >> 8) % 300000;
    const uint8_t addr = i % 3 == 0   ? kRefSwitches
                         : i % 3 == 1 ? motor_reg(1, kXActual)
                                      : motor_reg(0, kInterrupt);
    ASSERT_EQ(read(lazy, addr), read(eager, addr)) << "datagram " << i;
    if (i == 9000) {
      write(eager, motor_reg(0, kVTarget), 0xFFF & (uint32_t)-900);
      write(lazy, motor_reg(0, kVTarget), 0xFFF & (uint32_t)-900);
    }
    eager.advance_ns(step_ns);
    lazy.advance_ns(step_ns);
    eager.x_actual(0);
  }
  EXPECT_EQ(lazy.x_actual(0), eager.x_actual(0));
  EXPECT_EQ(lazy.v_actual_q8(0), eager.v_actual_q8(0));
  EXPECT_LT(lazy.motor_integrations(), eager.motor_integrations());
}

// The status byte of every answer covers all three motors: for one cruising far from
// x_target and its switches it is worked out once, not again for each datagram.
TEST(Tmc428Model, AStatusByteWorksOutACruisingMotorsReachOncePerChange) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kXTarget), 0xFFFFFF & (uint32_t)-1000);
  c.set_switch_positions(0, -200000, 200000);
  write(c, motor_reg(0, kVTarget), 300);
  c.advance_us(100000);  // at v 300: ~1.8 microsteps per 26 us datagram, far from both
  c.x_actual(0);
  read(c, motor_reg(1, kXActual));
  const uint64_t checks0 = c.reach_checks();
  for (int i = 0; i < 100; ++i) {
    read(c, motor_reg(1, kXActual));
    read(c, kRefSwitches);
    c.advance_us(26);
  }
  EXPECT_EQ(c.reach_checks(), checks0);
  write(c, motor_reg(0, kXTarget), 0);  // a change: worked out again at the next answer
  read(c, motor_reg(1, kXActual));
  EXPECT_EQ(c.reach_checks(), checks0 + 1);
}

// The status bits worked out ahead agree with integrating before every answer, for a
// motor creeping to and fro over x_target and onto a switch (Z hovering at its target).
TEST(Tmc428Model, StatusBitsAheadAgreeNearXTargetAndASwitch) {
  Tmc428Model eager, lazy;
  for (Tmc428Model* c : {&eager, &lazy}) {
    write(*c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
    velocity_setup(*c);
    write(*c, motor_reg(0, kXTarget), 40);
    c->set_switch_positions(0, -150, 100000);
  }
  uint32_t seed = 11;
  for (int i = 0; i < 20000; ++i) {
    seed = seed * 1103515245u + 12345u;
    if (i % 50 == 0) {  // a new small velocity either way, now and then x_target moved
      const int32_t v = (int32_t)((seed >> 8) % 801) - 400;
      for (Tmc428Model* c : {&eager, &lazy}) {
        write(*c, motor_reg(0, kVTarget), 0xFFF & (uint32_t)v);
        if (i % 450 == 0) write(*c, motor_reg(0, kXTarget), 0xFFFFFF & ((seed >> 4) % 200 - 100));
        if (i % 700 == 0) write(*c, motor_reg(0, kInterrupt), 0xFFFF);
      }
    }
    const uint32_t step_ns = 1000 + (seed >> 12) % 40000;
    const uint8_t addr = i % 2 == 0 ? kRefSwitches : motor_reg(2, kVMax);
    ASSERT_EQ(read(lazy, addr), read(eager, addr)) << "datagram " << i;
    eager.advance_ns(step_ns);
    lazy.advance_ns(step_ns);
    eager.x_actual(0);
  }
  EXPECT_EQ(lazy.x_actual(0), eager.x_actual(0));
}

// The firmware's tick reads every position and writes new velocities each millisecond: a
// motor far from x_target and its switches keeps the reach worked out once across those
// integrations and velocity changes (no more than a microstep a pulse clock either way).
TEST(Tmc428Model, AMovingMotorsReachOutlastsItsReadsAndNewVelocities) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kXTarget), 0xFFFFFF & (uint32_t)-100000);
  c.set_switch_positions(0, -200000, 200000);
  write(c, motor_reg(0, kVTarget), 300);
  c.advance_us(100000);
  read(c, motor_reg(0, kXActual));
  const uint64_t checks0 = c.reach_checks();
  const int32_t x0 = c.x_actual(0);
  for (int ms = 0; ms < 50; ++ms) {
    for (int m = 0; m < 3; ++m) read(c, motor_reg(m, kXActual));
    write(c, motor_reg(0, kVTarget), 300 + ms % 7);
    read(c, kRefSwitches);
    c.advance_us(1000);
  }
  EXPECT_EQ(c.reach_checks(), checks0);
  EXPECT_GT(c.x_actual(0), x0 + 400);   // it moved (~11 microsteps a millisecond)
  write(c, motor_reg(0, kXTarget), 0);  // a change: worked out again at the next answer
  read(c, motor_reg(1, kXActual));
  EXPECT_EQ(c.reach_checks(), checks0 + 1);
}

// Through the same tick, with velocities either way over x_target and onto the left switch,
// every answer's motor-1 status bits are what its position and flags say at that moment.
TEST(Tmc428Model, StatusBitsThroughTheTickAgreeWithThePosition) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c);
  write(c, motor_reg(0, kXTarget), 60);
  c.set_switch_positions(0, -900, 100000);
  uint32_t seed = 5;
  int crossings = 0, on_switch = 0;
  int32_t last_x = 0;
  for (int ms = 0; ms < 6000; ++ms) {
    seed = seed * 1103515245u + 12345u;
    // A few microsteps a millisecond, 0.7 s one way then the other: over x_target, onto
    // the switch and off it; at rest for the last 0.1 s of each way.
    const int32_t speed = ms % 700 >= 600 ? 0 : 20 + (int32_t)((seed >> 8) % 81);
    const int32_t v = (ms / 700) % 2 == 0 ? -speed : speed;
    for (int m = 0; m < 3; ++m) {
      const int32_t x = c.x_actual(0);
      const bool irq = (c.reg(0, 11) >> 8 & c.reg(0, 11) & 0xFF) != 0;
      const uint32_t expected =
          ((x & 0xFFFFFF) == 60 ? 0x01u : 0u) | (x <= -900 ? 0x02u : 0u) | (irq ? 0x80u : 0u);
      const uint32_t status = read(c, motor_reg(m, kXActual)) >> 24;
      ASSERT_EQ(status & 0x83u, expected) << "millisecond " << ms << ", x " << x;
      crossings += (last_x < 60) != (x < 60);
      on_switch += (status & 0x02u) != 0;
      last_x = x;
      c.advance_us(26);
    }
    write(c, motor_reg(0, kVTarget), 0xFFF & (uint32_t)v);
    if (ms % 1000 == 999) write(c, motor_reg(0, kInterrupt), 0xFFFF);  // flags cleared
    c.advance_us(900);
  }
  EXPECT_GE(crossings, 6);
  EXPECT_GT(on_switch, 0);
}

TEST(Tmc428Model, NegativeVelocityMovesBackwards) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVTarget), 0xFFF & (uint32_t)-300);
  c.advance_us(200000);
  EXPECT_EQ(c.v_actual(0), -300);
  EXPECT_LT(c.x_actual(0), 0);
}

TEST(Tmc428Model, VelocityIsLimitedToVMax) {
  Tmc428Model c;
  velocity_setup(c);
  write(c, motor_reg(0, kVMax), 200);
  write(c, motor_reg(0, kVTarget), 1500);
  c.advance_us(200000);
  EXPECT_EQ(c.v_actual(0), 200);
}

TEST(Tmc428Model, RampModeWithVMaxZeroDoesNotMove) {
  Tmc428Model c;
  write(c, motor_reg(0, kXTarget), 100000);
  write(c, motor_reg(0, kAMax), 100);
  c.advance_us(100000);
  EXPECT_EQ(c.x_actual(0), 0);
}

// ---- switches -------------------------------------------------------------------------

// Integrated in many short steps (the simulator reads x_actual and writes v_target every
// millisecond), a motor still stops exactly on the switch: the span known to be free of
// switches is worked out again when it ends, and when x_actual is written.
TEST(Tmc428Model, HardStopsExactlyOnTheSwitchWhenReadEveryMillisecond) {
  for (const bool jump : {false, true}) {
    Tmc428Model c;
    write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
    velocity_setup(c);
    c.set_switch_positions(0, -100000, 5000);
    write(c, motor_reg(0, kVTarget), 1000);
    for (int ms = 0; ms < 500; ++ms) {
      c.advance_us(1000);
      c.x_actual(0);
      write(c, motor_reg(0, kVTarget), 1000);
      if (jump && ms == 20) write(c, motor_reg(0, kXActual), 4900);  // the switch near
    }
    EXPECT_EQ(c.x_actual(0), 5000) << "jump " << jump;
    EXPECT_EQ(c.v_actual(0), 0) << "jump " << jump;
  }
}

TEST(Tmc428Model, HardStopsExactlyOnTheRightSwitch) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c);
  c.set_switch_positions(0, -100000, 5000);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(500000);
  EXPECT_EQ(c.x_actual(0), 5000);
  EXPECT_EQ(c.v_actual(0), 0);
  EXPECT_EQ(c.reg(0, 11) & kIntStop, kIntStop);
  EXPECT_EQ(c.switch_bits(), 0x01);  // r1
  EXPECT_EQ(c.status_byte() & kStatusInt, kStatusInt);
}

TEST(Tmc428Model, HardStopsOnTheLeftSwitchAndShowsRs1) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c);
  c.set_switch_positions(0, -3000, 100000);
  write(c, motor_reg(0, kVTarget), 0xFFF & (uint32_t)-1000);
  c.advance_us(500000);
  EXPECT_EQ(c.x_actual(0), -3000);
  EXPECT_EQ(c.status_byte() & kStatusRs1, kStatusRs1);
  EXPECT_EQ(c.switch_bits(), 0x02);  // l1
}

TEST(Tmc428Model, MovesAwayFromAnActiveSwitch) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c);
  c.set_switch_positions(0, -100000, 5000);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(500000);
  write(c, motor_reg(0, kVTarget), 0xFFF & (uint32_t)-1000);
  c.advance_us(200000);
  EXPECT_LT(c.x_actual(0), 5000);
  EXPECT_EQ(c.switch_bits(), 0);
}

TEST(Tmc428Model, SoftStopRampsDownPastTheSwitch) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c, kSoftStop);
  c.set_switch_positions(0, -100000, 5000);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(800000);
  EXPECT_EQ(c.v_actual(0), 0);
  // Braking from 1000 takes the ramp distance, 1420.5 usteps, beyond the switch.
  EXPECT_NEAR(c.x_actual(0), 5000 + 1420.5, 1420.5 * 0.01);
}

TEST(Tmc428Model, DisabledStopLetsTheMotorRunOverTheSwitch) {
  Tmc428Model c;
  write(c, kSmgp, kSmgpRefMux | kSmgpContinuousUpdate);
  velocity_setup(c, kDisableStopR);
  c.set_switch_positions(0, -100000, 5000);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(500000);
  EXPECT_GT(c.x_actual(0), 5000);
  EXPECT_EQ(c.switch_bits(), 0x01);
}

TEST(Tmc428Model, RightSwitchesExistOnlyWithRefmux) {
  Tmc428Model c;  // SMGP at power-on: refmux 0 -> REFn are left switches only
  velocity_setup(c);
  c.set_switch_positions(0, -100000, 5000);
  write(c, motor_reg(0, kVTarget), 1000);
  c.advance_us(500000);
  EXPECT_GT(c.x_actual(0), 5000);
}

// ---- driver chain ---------------------------------------------------------------------

// RAM chain table for three TMC246 and SMGP with LSMD 2, continuous update.
void chain_setup(Tmc428Model& c) {
  const uint32_t pairs[6] = {0x0507, 0x0304, 0x0602, 0x0D0F, 0x0B0C, 0x2E0A};
  for (int k = 0; k < 18; ++k) write(c, (uint8_t)(0x80 + 2 * k), pairs[k % 6]);
  write(c, kSmgp, 2 | (7 << 8) | kSmgpContinuousUpdate | kSmgpRefMux);
}

TEST(Tmc428Model, ChainReadbackPlacesMotor1InTheHighWord) {
  Tmc428Model c;
  chain_setup(c);
  c.set_driver_status(0, 0x111);
  c.set_driver_status(1, 0x322);
  c.set_driver_status(2, 0x533);
  write(c, kDatagramLowWord, 0);
  EXPECT_EQ(c.status_byte() & kStatusCdgw, kStatusCdgw);
  c.advance_us(5000);  // continuous update every 32768 / 3 ticks at ramp_div 0 (1.1 ms)
  EXPECT_EQ(c.status_byte() & kStatusCdgw, 0);
  EXPECT_EQ(datagram_data(read(c, kDatagramLowWord)), 0x322533u);
  EXPECT_EQ(datagram_data(read(c, kDatagramHighWord)) & 0xFFF, 0x111u);
}

TEST(Tmc428Model, ChainNeverAnswersWithoutContinuousUpdateAtRest) {
  Tmc428Model c;
  chain_setup(c);
  write(c, kSmgp, 2 | (7 << 8));
  write(c, kDatagramLowWord, 0);
  c.advance_us(100000);
  EXPECT_EQ(c.status_byte() & kStatusCdgw, kStatusCdgw);
}

TEST(Tmc428Model, ChainWithoutNxMNeverCompletes) {
  Tmc428Model c;
  for (int k = 0; k < 32; ++k) write(c, (uint8_t)(0x80 + 2 * k), 0x1111);
  write(c, kSmgp, 2 | (7 << 8) | kSmgpContinuousUpdate);
  write(c, kDatagramLowWord, 0);
  c.advance_us(100000);
  EXPECT_EQ(c.status_byte() & kStatusCdgw, kStatusCdgw);
}

TEST(Tmc428Model, LogsEveryDatagramWithItsTime) {
  Tmc428Model c;
  write(c, motor_reg(0, kVMin), 1);
  c.advance_us(250);
  read(c, motor_reg(0, kVMin));
  ASSERT_EQ(c.log().size(), 2u);
  EXPECT_EQ(c.log()[0].time_ns, 0u);
  EXPECT_EQ(c.log()[1].time_ns, 250000u);
  EXPECT_EQ(c.log()[1].mosi, 0x05000000u);
  EXPECT_EQ(c.log()[1].miso, 0x15000001u);
}

}  // namespace

namespace {

TEST(Tmc428ModelLog, StopsGrowingAtItsLimitAndCountsTheRest) {
  fake::Tmc428Model c;
  c.set_log_limit(2);
  for (int i = 0; i < 5; ++i) c.transfer32(0x05000000u);
  EXPECT_EQ(c.log().size(), 2u);
  EXPECT_EQ(c.log_dropped(), 3u);
}

}  // namespace
