// Interrupt priorities, vector routing, trap record and interrupt masking.
#include "hal/dspic30f6014/interrupts.h"

#include "hal/dspic30f6014/uart1.h"
#include "hal/interfaces/irq.h"
#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

class InterruptsTest : public FakeSfrTest {
 protected:
  InterruptsTest() { dspic::configure_interrupt_priorities(); }
  ~InterruptsTest() override {
    dspic::install_uart1(nullptr);
    dspic::install_tick(nullptr, nullptr);
  }
};

unsigned t1ip(const fake::DspicRegisters& r) {
  return (r.peek(kIPC0) >> 12) & 7;
}
unsigned u1rxip(const fake::DspicRegisters& r) {
  return (r.peek(kIPC2) >> 4) & 7;
}
unsigned u1txip(const fake::DspicRegisters& r) {
  return (r.peek(kIPC2) >> 8) & 7;
}

TEST_F(InterruptsTest, UartReceiveOutranksTheTick) {
  EXPECT_EQ(u1rxip(sfr), 6u);
  EXPECT_EQ(t1ip(sfr), 4u);
  EXPECT_GT(u1rxip(sfr), t1ip(sfr));
}

TEST_F(InterruptsTest, UartTransmitSitsBetweenReceiveAndTick) {
  EXPECT_EQ(u1txip(sfr), 5u);
  EXPECT_LT(u1txip(sfr), u1rxip(sfr));
  EXPECT_GT(u1txip(sfr), t1ip(sfr));
}

TEST_F(InterruptsTest, UnusedSourcesInTheseRegistersAreDisabled) {
  EXPECT_EQ(sfr.peek(kIPC0) & 0x0FFF, 0);  // INT0, IC1, OC1
  EXPECT_EQ(sfr.peek(kIPC2) & 0xF007, 0);  // SPI1, ADC
}

TEST_F(InterruptsTest, NestingIsEnabled) {
  sfr.poke(kINTCON1, 0x8000);
  dspic::configure_interrupt_priorities();
  EXPECT_EQ(sfr.peek(kINTCON1) & 0x8000, 0);  // NSTDIS = 0
}

int g_ticks = 0;
void count_tick(void* context) {
  ++*static_cast<int*>(context);
}

TEST_F(InterruptsTest, Timer1VectorClearsItsFlagAndRunsTheTick) {
  g_ticks = 0;
  dspic::install_tick(count_tick, &g_ticks);
  sfr.poke(kIFS0, 0x0008);
  _T1Interrupt();
  EXPECT_EQ(g_ticks, 1);
  EXPECT_EQ(sfr.peek(kIFS0) & 0x0008, 0);
}

TEST_F(InterruptsTest, Timer1VectorWithoutATickOnlyClearsTheFlag) {
  sfr.poke(kIFS0, 0x0008);
  _T1Interrupt();
  EXPECT_EQ(sfr.peek(kIFS0) & 0x0008, 0);
}

TEST_F(InterruptsTest, UartVectorsReachTheInstalledPort) {
  dspic::Uart1 uart;
  uart.init(115200);
  dspic::install_uart1(&uart);
  sfr.uart1_receive('Q');
  _U1RXInterrupt();
  uint8_t b = 0;
  ASSERT_TRUE(uart.read_byte(&b));
  EXPECT_EQ(b, 'Q');
  const uint8_t reply[] = {'*', 'O'};
  uart.write(reply, 2);
  _U1TXInterrupt();
  EXPECT_EQ(sfr.uart1_sent(), (std::vector<uint8_t>{'*', 'O'}));
}

TEST_F(InterruptsTest, UartVectorsWithoutAPortClearTheirFlags) {
  sfr.poke(kIFS0, 0x0600);
  _U1RXInterrupt();
  _U1TXInterrupt();
  EXPECT_EQ(sfr.peek(kIFS0) & 0x0600, 0);
}

TEST_F(InterruptsTest, AddressErrorTrapIsRecordedOnceAndItsFlagCleared) {
  dspic::take_trap_cause();
  sfr.poke(kINTCON1, 0x0008);
  _AddressError();
  EXPECT_EQ(sfr.peek(kINTCON1) & 0x0008, 0);
  EXPECT_EQ(dspic::take_trap_cause(), dspic::kTrapAddressError);
  EXPECT_EQ(dspic::take_trap_cause(), dspic::kTrapNone);
}

TEST_F(InterruptsTest, EachTrapHasItsOwnCause) {
  _StackError();
  EXPECT_EQ(dspic::take_trap_cause(), dspic::kTrapStackError);
  _MathError();
  EXPECT_EQ(dspic::take_trap_cause(), dspic::kTrapMathError);
  _OscillatorFail();
  EXPECT_EQ(dspic::take_trap_cause(), dspic::kTrapOscillatorFail);
}

TEST_F(InterruptsTest, ResetCauseIsReadAndCleared) {
  sfr.poke(kRCON, 0x8001);  // TRAPR + POR
  EXPECT_EQ(dspic::take_reset_cause(), 0x8001);
  EXPECT_EQ(sfr.peek(kRCON) & 0x80D3, 0);
}

TEST_F(InterruptsTest, IrqSaveRaisesCpuPriorityTo7) {
  sfr.poke(kSR, 0x0001);  // IPL 0, carry set
  const uint16_t saved = hal::irq_save();
  EXPECT_EQ((sfr.peek(kSR) >> 5) & 7, 7);
  EXPECT_EQ(sfr.peek(kSR) & 1, 1);  // other SR bits kept
  hal::irq_restore(saved);
  EXPECT_EQ((sfr.peek(kSR) >> 5) & 7, 0);
}

TEST_F(InterruptsTest, IrqSaveNests) {
  sfr.poke(kSR, 0);
  const uint16_t outer = hal::irq_save();
  const uint16_t inner = hal::irq_save();
  hal::irq_restore(inner);
  EXPECT_EQ((sfr.peek(kSR) >> 5) & 7, 7);  // still masked inside the outer section
  hal::irq_restore(outer);
  EXPECT_EQ((sfr.peek(kSR) >> 5) & 7, 0);
}

TEST_F(InterruptsTest, IrqGuardRestoresOnScopeExit) {
  sfr.poke(kSR, 0x0080);  // IPL 4 (running inside the tick)
  {
    hal::IrqGuard guard;
    EXPECT_EQ((sfr.peek(kSR) >> 5) & 7, 7);
  }
  EXPECT_EQ((sfr.peek(kSR) >> 5) & 7, 4);
}

}  // namespace
