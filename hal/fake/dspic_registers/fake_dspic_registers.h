// Host-only fake of the dsPIC30F6014 SFR space (0x0000-0x07FF, 2 KB) behind the port's
// Sfr16 accessors. Plain registers are memory; the peripherals the port drives have hooks:
// UART1 (4-deep RX FIFO fed by the test with FERR/PERR per byte and OERR on overflow, TX FIFO
// that the test drains), SPI1 (every SPI1BUF write is logged with the chip-select level and
// answered from a scripted MISO queue) and a cycle counter for the port's busy waits.
// One register file per process (the port reaches it through free functions); call
// reset() at the start of each test.
#ifndef HAL_FAKE_DSPIC_REGISTERS_FAKE_DSPIC_REGISTERS_H
#define HAL_FAKE_DSPIC_REGISTERS_FAKE_DSPIC_REGISTERS_H

#include <stdint.h>

#include <deque>
#include <functional>
#include <vector>

namespace fake {

class DspicRegisters {
 public:
  enum { kSfrBytes = 0x0800, kUartFifoDepth = 4 };

  // One access the port made, in order.
  struct Access {
    uint16_t address;
    uint16_t value;  // value written (whole register after the write)
  };
  // One 16-bit word the SPI1 master shifted.
  struct SpiWord {
    uint16_t mosi;
    uint16_t miso;
    uint16_t spi1con;  // SPI1CON at the time
    bool cs_low;       // TMC428 chip select (LATB bit 2) asserted
  };

  static DspicRegisters& instance();

  // Power-on state: all zero except TRISx = 0xFFFF and IPCn = 0x4444 (priority 4).
  void reset();

  // Raw memory, no side effects.
  uint16_t peek(uint16_t address) const;
  void poke(uint16_t address, uint16_t value);
  bool bit(uint16_t address, uint8_t n) const { return (peek(address) >> n) & 1u; }

  // ---- what the port's accessors call ----
  uint16_t read(uint16_t address);
  void write(uint16_t address, uint16_t value);
  void write_low_byte(uint16_t address, uint8_t value);
  void add_delay_cycles(uint32_t cycles) { delay_cycles_ += cycles; }

  // ---- UART1, line side ----
  // A byte arrives: into the RX FIFO (sets U1RXIF) or, with the FIFO full or OERR set, lost
  // with OERR set (reception stops until the port clears OERR, which empties the FIFO).
  void uart1_receive(uint8_t byte, bool framing_error = false, bool parity_error = false);
  // Bytes the port wrote to U1TXREG while the transmitter was enabled.
  const std::vector<uint8_t>& uart1_sent() const { return uart1_sent_; }
  // The transmitter shifted n bytes out of the TX FIFO (each sets U1TXIF, UTXISEL = 0).
  void uart1_shift_out(int n);
  int uart1_tx_fifo_level() const { return uart1_tx_level_; }
  int uart1_rx_fifo_level() const { return (int)uart1_rx_.size(); }
  // Writes to U1TXREG with the FIFO full (lost on real hardware).
  int uart1_tx_overflows() const { return uart1_tx_overflows_; }

  // ---- SPI1, slave side ----
  // Next word the slave shifts back (0 when the queue is empty).
  void spi1_queue_miso(uint16_t word) { spi1_miso_.push_back(word); }
  const std::vector<SpiWord>& spi1_words() const { return spi1_words_; }
  // When set, a transfer never completes (SPIRBF stays 0): a dead bus.
  void set_spi1_stalled(bool stalled) { spi1_stalled_ = stalled; }

  // ---- observation ----
  const std::vector<Access>& writes() const { return writes_; }
  uint64_t delay_cycles() const { return delay_cycles_; }
  // Called after every write (e.g. to feed LATD into a simulated LCD).
  std::function<void(uint16_t address, uint16_t value)> on_write;

 private:
  DspicRegisters();
  uint16_t u1sta_view() const;
  void store(uint16_t address, uint16_t value);

  uint16_t mem_[kSfrBytes / 2];
  uint64_t delay_cycles_;
  std::vector<Access> writes_;

  struct RxChar {
    uint8_t byte;
    bool framing_error;
    bool parity_error;
  };
  std::deque<RxChar> uart1_rx_;
  bool uart1_overrun_;
  int uart1_tx_level_;
  int uart1_tx_overflows_;
  std::vector<uint8_t> uart1_sent_;

  std::deque<uint16_t> spi1_miso_;
  uint16_t spi1_rx_word_;
  bool spi1_stalled_;
  std::vector<SpiWord> spi1_words_;
};

}  // namespace fake

#endif  // HAL_FAKE_DSPIC_REGISTERS_FAKE_DSPIC_REGISTERS_H
