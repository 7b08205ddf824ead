// Port setup: digital pins, outputs with their idle levels set first.
#include "hal/dspic30f6014/ports.h"

#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

class PortsTest : public FakeSfrTest {
 protected:
  PortsTest() { dspic::init_ports(); }
};

TEST_F(PortsTest, AllAnalogPinsAreDigital) {
  EXPECT_EQ(sfr.peek(kADPCFG), 0xFFFF);
}

TEST_F(PortsTest, TmcChipSelectRb2IsAnOutputIdlingHigh) {
  EXPECT_EQ(field(kTRISB, 2, 1), 0u);
  EXPECT_EQ(field(kLATB, 2, 1), 1u);
}

TEST_F(PortsTest, ChipSelectIsHighBeforeItBecomesAnOutput) {
  bool latched_high = false;
  for (const auto& w : sfr.writes()) {
    if (w.address == kLATB && (w.value & 0x0004)) latched_high = true;
    if (w.address == kTRISB && !(w.value & 0x0004)) {
      EXPECT_TRUE(latched_high);
      return;
    }
  }
  FAIL() << "TRISB2 never cleared";
}

TEST_F(PortsTest, PanelPinsRb8ToRb14StayInputs) {
  EXPECT_EQ(field(kTRISB, 8, 0x7F), 0x7Fu);
}

TEST_F(PortsTest, LcdBusRd0ToRd10AndSpindleRd11AreOutputsDrivenLow) {
  EXPECT_EQ(sfr.peek(kTRISD) & 0x0FFF, 0);
  EXPECT_EQ(sfr.peek(kLATD) & 0x0FFF, 0);
  EXPECT_EQ(sfr.peek(kTRISD) & 0xF000, 0xF000);
}

TEST_F(PortsTest, UartAndSpiPinDirections) {
  EXPECT_EQ(field(kTRISF, 2, 1), 1u);  // U1RX in
  EXPECT_EQ(field(kTRISF, 3, 1), 0u);  // U1TX out
  EXPECT_EQ(field(kLATF, 3, 1), 1u);   // idles high (mark)
  EXPECT_EQ(field(kTRISF, 6, 1), 0u);  // SCK1 out
  EXPECT_EQ(field(kLATF, 6, 1), 1u);   // idles high (CKP = 1)
  EXPECT_EQ(field(kTRISF, 7, 1), 1u);  // SDI1 in
  EXPECT_EQ(field(kTRISF, 8, 1), 0u);  // SDO1 out
}

}  // namespace
