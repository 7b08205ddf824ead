// The probe input on RA12 / INT1: an input, INT1 on the falling edge below the tick's
// priority, active low, and a touch shorter than a tick kept by the INT1 vector.
#include "hal/dspic30f6014/probe_pin.h"

#include "hal/dspic30f6014/interrupts.h"
#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

// Data sheet addresses (reference/dspic30f6014.md), not the port's.
enum : uint16_t {
  kINTCON2 = 0x0082,
  kIFS1 = 0x0086,
  kIEC1 = 0x008E,
  kIPC4 = 0x009C,
  kTRISA = 0x02C0,
  kPORTA = 0x02C2
};

class ProbePinTest : public FakeSfrTest {
 protected:
  ProbePinTest() {
    dspic::configure_interrupt_priorities();
    sfr.poke(kTRISA, 0);       // as if something had made it an output
    sfr.poke(kIFS1, 0x0001);   // a stale INT1 flag
    sfr.poke(kPORTA, 0x1000);  // RA12 high: open
    pin.init();
    dspic::install_probe(&pin);
  }
  ~ProbePinTest() override { dspic::install_probe(nullptr); }
  dspic::ProbePin pin;
};

TEST_F(ProbePinTest, Ra12IsAnInputWithInt1OnTheFallingEdgeEnabledBelowTheTick) {
  EXPECT_EQ(field(kTRISA, 12, 1), 1u);
  EXPECT_EQ(field(kINTCON2, 1, 1), 1u);  // INT1EP: falling edge
  EXPECT_EQ(field(kIPC4, 0, 7), 3u);     // INT1IP
  EXPECT_LT(field(kIPC4, 0, 7), (sfr.peek(kIPC0) >> 12) & 7u) << "below Timer1";
  EXPECT_EQ(field(kIFS1, 0, 1), 0u) << "the stale flag is cleared before enabling";
  EXPECT_EQ(field(kIEC1, 0, 1), 1u);
  bool flag_cleared = false;
  for (const auto& w : sfr.writes()) {
    if (w.address == kIFS1 && !(w.value & 1)) flag_cleared = true;
    if (w.address == kIEC1 && (w.value & 1)) {
      EXPECT_TRUE(flag_cleared);
      break;
    }
  }
}

TEST_F(ProbePinTest, ClosedWhileRa12ReadsLow) {
  EXPECT_FALSE(pin.closed());
  sfr.poke(kPORTA, 0x0000);
  EXPECT_TRUE(pin.closed());
  EXPECT_TRUE(pin.closed());
  sfr.poke(kPORTA, 0x1000);
  EXPECT_FALSE(pin.closed());
  sfr.poke(kPORTA, 0xEFFF);  // other port A pins do not matter
  EXPECT_TRUE(pin.closed());
}

TEST_F(ProbePinTest, ATouchBetweenTwoTicksIsSeenOnceThroughInt1) {
  sfr.poke(kIFS1, 0x0001);
  _INT1Interrupt();  // the pin fell and rose again between two ticks
  EXPECT_EQ(field(kIFS1, 0, 1), 0u);
  EXPECT_TRUE(pin.closed());
  EXPECT_FALSE(pin.closed()) << "the edge counts once";
}

TEST_F(ProbePinTest, Int1VectorWithoutAProbeOnlyClearsTheFlag) {
  dspic::install_probe(nullptr);
  sfr.poke(kIFS1, 0x0001);
  _INT1Interrupt();
  EXPECT_EQ(field(kIFS1, 0, 1), 0u);
  EXPECT_FALSE(pin.closed());
}

}  // namespace
