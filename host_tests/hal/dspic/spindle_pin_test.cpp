// The spindle output on RD11: off after port set-up, switched by LATD bit 11 only.
#include "hal/dspic30f6014/spindle_pin.h"

#include "hal/dspic30f6014/ports.h"
#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

class SpindlePinTest : public FakeSfrTest {
 protected:
  SpindlePinTest() { dspic::init_ports(); }
  dspic::SpindlePin pin;
};

TEST_F(SpindlePinTest, Rd11IsAnOutputDrivenLowAfterPortSetUp) {
  EXPECT_EQ(field(kTRISD, 11, 1), 0u);
  EXPECT_EQ(field(kLATD, 11, 1), 0u);
}

TEST_F(SpindlePinTest, LowIsLatchedBeforeRd11BecomesAnOutput) {
  bool latched_low = false;
  for (const auto& w : sfr.writes()) {
    if (w.address == kLATD && !(w.value & 0x0800)) latched_low = true;
    if (w.address == kTRISD && !(w.value & 0x0800)) {
      EXPECT_TRUE(latched_low);
      return;
    }
  }
  FAIL() << "TRISD11 never cleared";
}

TEST_F(SpindlePinTest, OnSetsOnlyLatd11AndOffClearsIt) {
  sfr.poke(kLATD, 0x05A5);  // an LCD byte on the bus must survive
  pin.set_on(true);
  EXPECT_EQ(sfr.peek(kLATD), 0x0DA5);
  pin.set_on(false);
  EXPECT_EQ(sfr.peek(kLATD), 0x05A5);
}

}  // namespace
