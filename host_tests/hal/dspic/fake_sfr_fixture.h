// Test fixture: a freshly reset fake SFR file for each test.
#ifndef HOST_TESTS_HAL_DSPIC_FAKE_SFR_FIXTURE_H
#define HOST_TESTS_HAL_DSPIC_FAKE_SFR_FIXTURE_H

#include <gtest/gtest.h>

#include "hal/fake/dspic_registers/fake_dspic_registers.h"

class FakeSfrTest : public ::testing::Test {
 protected:
  FakeSfrTest() : sfr(fake::DspicRegisters::instance()) { sfr.reset(); }
  ~FakeSfrTest() override { sfr.reset(); }
  // One field of a register: (value >> shift) & mask.
  unsigned field(uint16_t address, int shift, unsigned mask) const {
    return (sfr.peek(address) >> shift) & mask;
  }
  fake::DspicRegisters& sfr;
};

// Data sheet addresses, written out here (reference/dspic30f6014.md) rather than taken from
// the port, so a wrong address in the port fails the tests.
enum : uint16_t {
  kSR = 0x0042,
  kRCON = 0x0740,
  kINTCON1 = 0x0080,
  kIFS0 = 0x0084,
  kIEC0 = 0x008C,
  kIPC0 = 0x0094,
  kIPC2 = 0x0098,
  kTMR1 = 0x0100,
  kPR1 = 0x0102,
  kT1CON = 0x0104,
  kU1MODE = 0x020C,
  kU1STA = 0x020E,
  kU1TXREG = 0x0210,
  kU1BRG = 0x0214,
  kSPI1STAT = 0x0220,
  kSPI1CON = 0x0222,
  kSPI1BUF = 0x0224,
  kADPCFG = 0x02A8,
  kTRISB = 0x02C6,
  kPORTB = 0x02C8,
  kLATB = 0x02CA,
  kTRISD = 0x02D2,
  kLATD = 0x02D6,
  kTRISF = 0x02DE,
  kLATF = 0x02E2
};

#endif  // HOST_TESTS_HAL_DSPIC_FAKE_SFR_FIXTURE_H
