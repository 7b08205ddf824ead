// Fake dsPIC30F6014 SFR file: memory plus the UART1/SPI1 behaviour the port relies on
// (dsPIC30F Family Reference Manual, UART sec. 19.3 and SPI sec. 20.4).
#include "hal/fake/dspic_registers/fake_dspic_registers.h"

#include <cstring>

#include "hal/dspic30f6014/pins.h"
#include "hal/dspic30f6014/registers.h"

namespace fake {

namespace {
// Addresses as plain numbers, from the port's own register map.
const uint16_t kU1STA = dspic::U1STA::address, kU1TXREG = dspic::U1TXREG::address,
               kU1RXREG = dspic::U1RXREG::address;
const uint16_t kSPI1STAT = dspic::SPI1STAT::address, kSPI1CON = dspic::SPI1CON::address,
               kSPI1BUF = dspic::SPI1BUF::address;
const uint16_t kIFS0 = dspic::IFS0::address, kLATB = dspic::LATB::address;
// TRISA, TRISB, TRISC, TRISD, TRISF, TRISG; IPC0..IPC10 (reference sec. 5, sec. 6).
const uint16_t kTris[] = {0x02C0, 0x02C6, 0x02CC, 0x02D2, 0x02DE, 0x02E4};
const uint16_t kIpcFirst = 0x0094, kIpcLast = 0x00A8;
// U1STA bits the hardware owns (read-only or set by hardware).
const uint16_t kU1staHardwareBits =
    (1u << dspic::U1STAbits::URXDA) | (1u << dspic::U1STAbits::OERR) |
    (1u << dspic::U1STAbits::FERR) | (1u << dspic::U1STAbits::PERR) |
    (1u << dspic::U1STAbits::RIDLE) | (1u << dspic::U1STAbits::TRMT) |
    (1u << dspic::U1STAbits::UTXBF);
}  // namespace

DspicRegisters& DspicRegisters::instance() {
  static DspicRegisters registers;
  return registers;
}

DspicRegisters::DspicRegisters() {
  reset();
}

void DspicRegisters::reset() {
  std::memset(mem_, 0, sizeof mem_);
  for (uint16_t tris : kTris) mem_[tris / 2] = 0xFFFF;
  for (uint16_t a = kIpcFirst; a <= kIpcLast; a += 2) mem_[a / 2] = 0x4444;
  delay_cycles_ = 0;
  writes_.clear();
  uart1_rx_.clear();
  uart1_overrun_ = false;
  uart1_tx_level_ = 0;
  uart1_tx_overflows_ = 0;
  uart1_sent_.clear();
  spi1_miso_.clear();
  spi1_rx_word_ = 0;
  spi1_stalled_ = false;
  spi1_words_.clear();
  on_write = nullptr;
}

uint16_t DspicRegisters::peek(uint16_t address) const {
  if (address >= kSfrBytes) return 0;
  if ((address & ~1u) == kU1STA) return u1sta_view();
  return mem_[address / 2];
}

void DspicRegisters::poke(uint16_t address, uint16_t value) {
  if (address < kSfrBytes) mem_[address / 2] = value;
}

// U1STA as the port reads it: stored control bits plus the live FIFO state.
uint16_t DspicRegisters::u1sta_view() const {
  using namespace dspic::U1STAbits;
  uint16_t v = (uint16_t)(mem_[kU1STA / 2] & ~kU1staHardwareBits);
  if (!uart1_rx_.empty()) {
    v |= 1u << URXDA;
    if (uart1_rx_.front().framing_error) v |= 1u << FERR;
    if (uart1_rx_.front().parity_error) v |= 1u << PERR;
  } else {
    v |= 1u << RIDLE;
  }
  if (uart1_overrun_) v |= 1u << OERR;
  if (uart1_tx_level_ >= kUartFifoDepth) v |= 1u << UTXBF;
  if (uart1_tx_level_ == 0) v |= 1u << TRMT;
  return v;
}

uint16_t DspicRegisters::read(uint16_t address) {
  address &= (uint16_t)~1u;
  if (address == kU1RXREG) {
    if (uart1_rx_.empty()) return 0;
    const uint8_t byte = uart1_rx_.front().byte;
    uart1_rx_.pop_front();
    return byte;
  }
  if (address == kSPI1BUF) {
    mem_[kSPI1STAT / 2] &= (uint16_t) ~(1u << dspic::SPI1STATbits::SPIRBF);
    return spi1_rx_word_;
  }
  return peek(address);
}

void DspicRegisters::store(uint16_t address, uint16_t value) {
  mem_[address / 2] = value;
  writes_.push_back(Access{address, value});
  if (on_write) on_write(address, value);
}

void DspicRegisters::write(uint16_t address, uint16_t value) {
  address &= (uint16_t)~1u;
  if (address >= kSfrBytes) return;
  if (address == kU1STA) {
    using namespace dspic::U1STAbits;
    // Clearing a set OERR empties the receive FIFO and restarts reception [FRM].
    if (uart1_overrun_ && !(value & (1u << OERR))) {
      uart1_overrun_ = false;
      uart1_rx_.clear();
    }
    store(address, (uint16_t)(value & ~kU1staHardwareBits));
    return;
  }
  if (address == kU1TXREG) {
    store(address, value);
    const bool enabled = (mem_[kU1STA / 2] >> dspic::U1STAbits::UTXEN) & 1u;
    if (!enabled) return;
    if (uart1_tx_level_ >= kUartFifoDepth) {
      ++uart1_tx_overflows_;
      return;
    }
    ++uart1_tx_level_;
    uart1_sent_.push_back((uint8_t)value);
    return;
  }
  if (address == kSPI1BUF) {
    store(address, value);
    const bool enabled = (mem_[kSPI1STAT / 2] >> dspic::SPI1STATbits::SPIEN) & 1u;
    if (!enabled || spi1_stalled_) return;
    const uint16_t miso = spi1_miso_.empty() ? 0 : spi1_miso_.front();
    if (!spi1_miso_.empty()) spi1_miso_.pop_front();
    const bool cs_low = !((mem_[kLATB / 2] >> dspic::pins::kTmcCsBit) & 1u);
    spi1_words_.push_back(SpiWord{value, miso, mem_[kSPI1CON / 2], cs_low});
    if (mem_[kSPI1STAT / 2] & (1u << dspic::SPI1STATbits::SPIRBF))
      mem_[kSPI1STAT / 2] |= 1u << dspic::SPI1STATbits::SPIROV;
    spi1_rx_word_ = miso;
    mem_[kSPI1STAT / 2] |= 1u << dspic::SPI1STATbits::SPIRBF;
    return;
  }
  store(address, value);
}

void DspicRegisters::write_low_byte(uint16_t address, uint8_t value) {
  address &= (uint16_t)~1u;
  if (address >= kSfrBytes) return;
  write(address, (uint16_t)((mem_[address / 2] & 0xFF00u) | value));
}

void DspicRegisters::uart1_receive(uint8_t byte, bool framing_error, bool parity_error) {
  if (uart1_overrun_ || (int)uart1_rx_.size() >= kUartFifoDepth) {
    uart1_overrun_ = true;
    return;
  }
  uart1_rx_.push_back(RxChar{byte, framing_error, parity_error});
  mem_[kIFS0 / 2] |= 1u << dspic::IFS0bits::U1RXIF;
}

void DspicRegisters::uart1_shift_out(int n) {
  for (int i = 0; i < n && uart1_tx_level_ > 0; ++i) {
    --uart1_tx_level_;
    mem_[kIFS0 / 2] |= 1u << dspic::IFS0bits::U1TXIF;
  }
}

}  // namespace fake

// The port's host accessors (declared in hal/dspic30f6014/sfr.h).
namespace dspic {
namespace host {

uint16_t sfr_read(uint16_t address) {
  return fake::DspicRegisters::instance().read(address);
}

void sfr_write(uint16_t address, uint16_t value) {
  fake::DspicRegisters::instance().write(address, value);
}

void sfr_write_low_byte(uint16_t address, uint8_t value) {
  fake::DspicRegisters::instance().write_low_byte(address, value);
}

// Like the target's BSET: no read side effects (no FIFO pop, no SPIRBF clear).
void sfr_set_bit(uint16_t address, uint8_t n) {
  fake::DspicRegisters& r = fake::DspicRegisters::instance();
  r.write(address, (uint16_t)(r.peek(address) | (1u << n)));
}

void sfr_clear_bit(uint16_t address, uint8_t n) {
  fake::DspicRegisters& r = fake::DspicRegisters::instance();
  r.write(address, (uint16_t)(r.peek(address) & ~(1u << n)));
}

void delay_cycles(uint32_t cycles) {
  fake::DspicRegisters::instance().add_delay_cycles(cycles);
}

}  // namespace host
}  // namespace dspic
