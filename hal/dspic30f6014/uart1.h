// UART1 to the XPort (or a USB-serial cable): 8N1, interrupt-driven both ways. The RX
// interrupt moves bytes from the 4-deep hardware FIFO into an SPSC ring the main loop reads;
// write() queues into a TX ring the TX interrupt drains into the hardware FIFO.
// Implements hal::SerialPort.
#ifndef HAL_DSPIC30F6014_UART1_H
#define HAL_DSPIC30F6014_UART1_H

#include <stdint.h>  // uint8_t, uint16_t, uint32_t

#include "firmware/config/machine_config.h"  // kLinkRxBufferBytes
#include "firmware/core/spsc_ring.h"         // core::SpscRing
#include "hal/interfaces/serial_port.h"      // hal::SerialPort

namespace dspic {

#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
// A concrete port object, never deleted through a base pointer.
class Uart1 : public hal::SerialPort {
 public:
  // 256 bytes = 22 ms of input at full line rate; 128 bytes of replies in flight.
  enum { kRxCapacity = config::kLinkRxBufferBytes, kTxCapacity = 128, kHardwareFifoDepth = 4 };

  Uart1();
  // UxBRG for a baud rate at an instruction clock: Fcy / (16 * baud) - 1, rounded to the
  // nearest divider (no BRGH on the dsPIC30F). 115200 at 20 MHz -> 10 (113 636 Bd, -1.4 %).
  static uint16_t brg_for(uint32_t fcy_hz, uint32_t baud);
  // Configures 8N1 at baud, clears and enables the RX/TX interrupts (their priorities are
  // set by configure_interrupt_priorities()), enables the UART and its transmitter.
  void init(uint32_t baud);

  // hal::SerialPort (main loop side)
  virtual bool read_byte(uint8_t* byte);
  virtual uint16_t write(const uint8_t* data, uint16_t len);
  virtual uint16_t write_space() const;
  virtual uint16_t take_rx_errors();

  // Interrupt side, called by the U1RX / U1TX vectors.
  void on_rx_interrupt();
  void on_tx_interrupt();

  // Error counts since init by kind (diagnostics; each also counts in take_rx_errors()).
  uint16_t overruns() const { return overruns_; }
  uint16_t framing_errors() const { return framing_errors_; }
  uint16_t ring_overflows() const { return ring_overflows_; }

 private:
  core::SpscRing<uint8_t, kRxCapacity> rx_;  // RX ISR -> main loop
  core::SpscRing<uint8_t, kTxCapacity> tx_;  // main loop -> TX ISR
  // Single-writer counters (16-bit loads/stores are atomic on the dsPIC): the RX ISR only
  // increments rx_errors_, the main loop only writes rx_errors_taken_.
  volatile uint16_t rx_errors_;
  uint16_t rx_errors_taken_;
  volatile uint16_t overruns_;
  volatile uint16_t framing_errors_;
  volatile uint16_t ring_overflows_;
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_UART1_H
