// Timer1: a 1 ms period from Fcy with 1:1 prescale.
#include "hal/dspic30f6014/timer1.h"

#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

class Timer1Test : public FakeSfrTest {
 protected:
  Timer1Test() { dspic::timer1_start_1ms(); }
};

TEST_F(Timer1Test, PeriodRegisterIs19999) {
  EXPECT_EQ(sfr.peek(kPR1), 19999);
}

TEST_F(Timer1Test, PeriodAndPrescaleGiveOneMillisecond) {
  const int prescale[4] = {1, 8, 64, 256};
  const double period_s = (sfr.peek(kPR1) + 1.0) * prescale[field(kT1CON, 4, 3)] / 20e6;
  EXPECT_DOUBLE_EQ(period_s, 1e-3);
}

TEST_F(Timer1Test, RunsFromFcyUngated) {
  EXPECT_EQ(field(kT1CON, 15, 1), 1u);  // TON
  EXPECT_EQ(field(kT1CON, 1, 1), 0u);   // TCS = 0: Fcy
  EXPECT_EQ(field(kT1CON, 6, 1), 0u);   // TGATE = 0
  EXPECT_EQ(sfr.peek(kTMR1), 0);
}

TEST_F(Timer1Test, InterruptIsEnabledWithItsFlagClear) {
  EXPECT_EQ(field(kIEC0, 3, 1), 1u);  // T1IE
  EXPECT_EQ(field(kIFS0, 3, 1), 0u);  // T1IF
}

TEST_F(Timer1Test, TimerIsStartedLast) {
  ASSERT_FALSE(sfr.writes().empty());
  EXPECT_EQ(sfr.writes().back().address, kT1CON);
}

}  // namespace
