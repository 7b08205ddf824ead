// UART1: 115200 8N1 register settings, RX interrupt into the ring with error handling, TX
// through the ring and the TX interrupt.
#include "hal/dspic30f6014/uart1.h"

#include <vector>

#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

class Uart1Test : public FakeSfrTest {
 protected:
  Uart1Test() { uart.init(115200); }
  std::vector<uint8_t> read_all() {
    std::vector<uint8_t> out;
    uint8_t b;
    while (uart.read_byte(&b)) out.push_back(b);
    return out;
  }
  dspic::Uart1 uart;
};

TEST_F(Uart1Test, InitSetsBrg10For115200At20Mips) {
  EXPECT_EQ(sfr.peek(kU1BRG), 10);
}

TEST_F(Uart1Test, Brg10GivesWithin1_5PercentOf115200) {
  const double actual = 20e6 / (16.0 * (sfr.peek(kU1BRG) + 1));  // 113 636 Bd
  EXPECT_NEAR(actual, 113636.0, 1.0);
  EXPECT_NEAR((actual - 115200.0) / 115200.0, -0.0136, 0.0005);
}

TEST_F(Uart1Test, BrgRoundsToTheNearestDivider) {
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 9600), 129);
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 19200), 64);
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 57600), 21);
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 115200), 10);
}

TEST_F(Uart1Test, BrgForImpossibleRatesStaysInRange) {
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 0), 0xFFFF);
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 5000000), 0);
  EXPECT_EQ(dspic::Uart1::brg_for(20000000, 10), 0xFFFF);
}

TEST_F(Uart1Test, InitEnablesUartEightDataBitsNoParityOneStop) {
  EXPECT_EQ(field(kU1MODE, 15, 1), 1u);  // UARTEN
  EXPECT_EQ(field(kU1MODE, 1, 3), 0u);   // PDSEL = 00: 8 bits, no parity
  EXPECT_EQ(field(kU1MODE, 0, 1), 0u);   // STSEL = 0: one stop bit
  EXPECT_EQ(field(kU1MODE, 10, 1), 0u);  // ALTIO = 0: U1RX/U1TX on RF2/RF3
  EXPECT_EQ(field(kU1MODE, 6, 1), 0u);   // no loopback
}

TEST_F(Uart1Test, InitEnablesTransmitterAndBothInterrupts) {
  EXPECT_EQ(field(kU1STA, 10, 1), 1u);  // UTXEN
  EXPECT_EQ(field(kU1STA, 6, 3), 0u);   // URXISEL = 00: interrupt per character
  EXPECT_EQ(field(kIEC0, 9, 1), 1u);    // U1RXIE
  EXPECT_EQ(field(kIEC0, 10, 1), 1u);   // U1TXIE
}

TEST_F(Uart1Test, TransmitterIsEnabledAfterTheUart) {
  int uarten_at = -1, utxen_at = -1;
  const auto& w = sfr.writes();
  for (size_t i = 0; i < w.size(); ++i) {
    if (w[i].address == kU1MODE && (w[i].value & 0x8000) && uarten_at < 0) uarten_at = (int)i;
    if (w[i].address == kU1STA && (w[i].value & 0x0400) && utxen_at < 0) utxen_at = (int)i;
  }
  ASSERT_GE(uarten_at, 0);
  EXPECT_GT(utxen_at, uarten_at);
}

TEST_F(Uart1Test, RxInterruptMovesBytesIntoTheRing) {
  sfr.uart1_receive('#');
  sfr.uart1_receive('S');
  sfr.uart1_receive('1');
  uart.on_rx_interrupt();
  EXPECT_EQ(read_all(), (std::vector<uint8_t>{'#', 'S', '1'}));
  EXPECT_EQ(uart.take_rx_errors(), 0);
}

TEST_F(Uart1Test, RxInterruptClearsItsFlag) {
  sfr.uart1_receive('A');
  ASSERT_EQ(field(kIFS0, 9, 1), 1u);
  uart.on_rx_interrupt();
  EXPECT_EQ(field(kIFS0, 9, 1), 0u);
}

TEST_F(Uart1Test, FramingErrorDropsTheByteAndCountsOnce) {
  sfr.uart1_receive('A');
  sfr.uart1_receive(0x55, /*framing_error=*/true);
  sfr.uart1_receive('B');
  uart.on_rx_interrupt();
  EXPECT_EQ(read_all(), (std::vector<uint8_t>{'A', 'B'}));
  EXPECT_EQ(uart.framing_errors(), 1);
  EXPECT_EQ(uart.take_rx_errors(), 1);
}

TEST_F(Uart1Test, OverrunKeepsTheFourFifoBytesClearsOerrAndCounts) {
  for (uint8_t b = '1'; b <= '6'; ++b) sfr.uart1_receive(b);  // 5th and 6th lost
  ASSERT_EQ(field(kU1STA, 1, 1), 1u);                         // OERR
  uart.on_rx_interrupt();
  EXPECT_EQ(read_all(), (std::vector<uint8_t>{'1', '2', '3', '4'}));
  EXPECT_EQ(field(kU1STA, 1, 1), 0u);
  EXPECT_EQ(uart.overruns(), 1);
  EXPECT_EQ(uart.take_rx_errors(), 1);
}

TEST_F(Uart1Test, ReceptionResumesAfterOverrunIsCleared) {
  for (int i = 0; i < 5; ++i) sfr.uart1_receive('x');
  uart.on_rx_interrupt();
  read_all();
  sfr.uart1_receive('y');
  uart.on_rx_interrupt();
  EXPECT_EQ(read_all(), (std::vector<uint8_t>{'y'}));
}

TEST_F(Uart1Test, FullRingCountsLostBytes) {
  const int capacity = dspic::Uart1::kRxCapacity;
  for (int i = 0; i < capacity + 3; ++i) {
    sfr.uart1_receive((uint8_t)i);
    uart.on_rx_interrupt();
  }
  EXPECT_EQ(uart.ring_overflows(), 3);
  EXPECT_EQ((int)read_all().size(), capacity);
}

TEST_F(Uart1Test, TakeRxErrorsReportsEachErrorOnce) {
  sfr.uart1_receive('a', true);
  uart.on_rx_interrupt();
  EXPECT_EQ(uart.take_rx_errors(), 1);
  EXPECT_EQ(uart.take_rx_errors(), 0);
  sfr.uart1_receive('b', false, /*parity_error=*/true);
  sfr.uart1_receive('c', true);
  uart.on_rx_interrupt();
  EXPECT_EQ(uart.take_rx_errors(), 2);
}

TEST_F(Uart1Test, WriteQueuesAndKicksTheTxInterrupt) {
  const uint8_t text[] = {'*', 'O'};
  sfr.poke(kIFS0, 0);
  EXPECT_EQ(uart.write(text, 2), 2);
  EXPECT_TRUE(sfr.uart1_sent().empty());  // nothing touches U1TXREG outside the ISR
  EXPECT_EQ(field(kIFS0, 10, 1), 1u);     // U1TXIF set by software
}

TEST_F(Uart1Test, TxInterruptFillsTheFourDeepFifoInOrder) {
  const uint8_t text[] = {'a', 'b', 'c', 'd', 'e', 'f'};
  uart.write(text, 6);
  uart.on_tx_interrupt();
  EXPECT_EQ(sfr.uart1_sent(), (std::vector<uint8_t>{'a', 'b', 'c', 'd'}));
  EXPECT_EQ(field(kIFS0, 10, 1), 0u);
  EXPECT_EQ(sfr.uart1_tx_overflows(), 0);
  sfr.uart1_shift_out(2);
  uart.on_tx_interrupt();
  EXPECT_EQ(sfr.uart1_sent(), (std::vector<uint8_t>{'a', 'b', 'c', 'd', 'e', 'f'}));
}

TEST_F(Uart1Test, WriteTakesOnlyWhatFits) {
  std::vector<uint8_t> big(dspic::Uart1::kTxCapacity + 10, 'z');
  EXPECT_EQ(uart.write(big.data(), (uint16_t)big.size()), dspic::Uart1::kTxCapacity);
  EXPECT_EQ(uart.write_space(), 0);
  uart.on_tx_interrupt();
  EXPECT_EQ(uart.write_space(), 4);
}

TEST_F(Uart1Test, NullPointersAreRefused) {
  EXPECT_EQ(uart.write(nullptr, 5), 0);
  EXPECT_FALSE(uart.read_byte(nullptr));
}

}  // namespace
