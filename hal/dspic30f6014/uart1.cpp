// UART1: register setup per the dsPIC30F FRM sec. 19.3 and the ring-buffered interrupt handlers.
#include "hal/dspic30f6014/uart1.h"

#include "hal/dspic30f6014/clock.h"      // kFcyHz
#include "hal/dspic30f6014/registers.h"  // U1MODE, U1STA, U1TXREG, U1RXREG, U1BRG, IFS0, IEC0

namespace dspic {

Uart1::Uart1()
    : rx_errors_(0), rx_errors_taken_(0), overruns_(0), framing_errors_(0), ring_overflows_(0) {}

// Baud = Fcy / (16 (UxBRG + 1)); rounding to the nearest divider keeps the error smallest.
uint16_t Uart1::brg_for(uint32_t fcy_hz, uint32_t baud) {
  if (baud == 0) return 0xFFFF;
  const uint32_t divider = (fcy_hz + 8u * baud) / (16u * baud);  // UxBRG + 1
  if (divider == 0) return 0;
  if (divider > 0x10000UL) return 0xFFFF;
  return (uint16_t)(divider - 1u);
}

// UARTEN before UTXEN: the transmitter can only be enabled on a running UART.
void Uart1::init(uint32_t baud) {
  U1MODE::write(0);  // off while configuring; PDSEL = 00 (8 bits, no parity), STSEL = 0
  U1BRG::write(brg_for(kFcyHz, baud));
  // UTXISEL = 0: TX interrupt whenever a character moves to the shift register (room in
  // the FIFO); URXISEL = 00: RX interrupt for every character received.
  U1STA::write(0);
  IFS0::clear_bit<IFS0bits::U1RXIF>();
  IFS0::clear_bit<IFS0bits::U1TXIF>();
  IEC0::set_bit<IEC0bits::U1RXIE>();
  IEC0::set_bit<IEC0bits::U1TXIE>();
  U1MODE::write(bit(U1MODEbits::UARTEN));
  U1STA::set_bit<U1STAbits::UTXEN>();
}

bool Uart1::read_byte(uint8_t* byte) {
  if (byte == 0) return false;
  return rx_.pop(byte);
}

// Queues what fits and kicks the TX interrupt by setting its flag (one BSET), so the
// ISR stays the only consumer of the TX ring.
uint16_t Uart1::write(const uint8_t* data, uint16_t len) {
  if (data == 0) return 0;
  uint16_t taken = 0;
  while (taken < len && tx_.push(data[taken])) ++taken;
  if (taken != 0) IFS0::set_bit<IFS0bits::U1TXIF>();
  return taken;
}

uint16_t Uart1::write_space() const {
  return tx_.free_space();
}

// Difference of two free-running single-writer counters, so no count is lost or doubled.
uint16_t Uart1::take_rx_errors() {
  const uint16_t total = rx_errors_;
  const uint16_t fresh = (uint16_t)(total - rx_errors_taken_);
  rx_errors_taken_ = total;
  return fresh;
}

// Drains the hardware FIFO. FERR/PERR in U1STA belong to the character at the top of the
// FIFO, so they are read before U1RXREG; such characters are dropped (the frame CRC and
// the parser's resynchronisation recover). OERR is cleared only after the FIFO is read,
// because clearing it empties the FIFO.
void Uart1::on_rx_interrupt() {
  IFS0::clear_bit<IFS0bits::U1RXIF>();  // first: a character arriving meanwhile re-flags
  for (uint8_t i = 0; i <= kHardwareFifoDepth; ++i) {
    const uint16_t status = U1STA::read();
    if (!(status & bit(U1STAbits::URXDA))) break;
    const uint8_t byte = (uint8_t)U1RXREG::read();
    if (status & (bit(U1STAbits::FERR) | bit(U1STAbits::PERR))) {
      framing_errors_ = (uint16_t)(framing_errors_ + 1);
      rx_errors_ = (uint16_t)(rx_errors_ + 1);
      continue;
    }
    if (!rx_.push(byte)) {  // main loop fell behind: the byte is lost, the CRC will say so
      ring_overflows_ = (uint16_t)(ring_overflows_ + 1);
      rx_errors_ = (uint16_t)(rx_errors_ + 1);
    }
  }
  if (U1STA::test_bit<U1STAbits::OERR>()) {
    U1STA::clear_bit<U1STAbits::OERR>();
    overruns_ = (uint16_t)(overruns_ + 1);
    rx_errors_ = (uint16_t)(rx_errors_ + 1);
  }
}

// Tops up the hardware TX FIFO from the ring; with nothing queued it just returns and the
// next write() kicks it again.
void Uart1::on_tx_interrupt() {
  IFS0::clear_bit<IFS0bits::U1TXIF>();
  uint8_t byte;
  for (uint8_t i = 0; i < kHardwareFifoDepth; ++i) {
    if (U1STA::test_bit<U1STAbits::UTXBF>()) break;
    if (!tx_.pop(&byte)) break;
    U1TXREG::write(byte);
  }
}

}  // namespace dspic
