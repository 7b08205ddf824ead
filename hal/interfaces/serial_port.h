// The host link (XPort or USB serial) as the application sees it. Received bytes arrive
// through an SPSC ring the UART RX interrupt fills; transmission is non-blocking.
#ifndef HAL_INTERFACES_SERIAL_PORT_H
#define HAL_INTERFACES_SERIAL_PORT_H

#include <stdint.h>  // uint8_t

namespace hal {

class SerialPort {
 public:
  // Next received byte, false if none. Called from the main loop only.
  virtual bool read_byte(uint8_t* byte) = 0;
  // Queues bytes for transmission; returns how many were taken (0..len), never blocks.
  virtual uint16_t write(const uint8_t* data, uint16_t len) = 0;
  // Bytes that write() would take right now.
  virtual uint16_t write_space() const = 0;
  // Receive errors (overrun, framing) since the last call; the parser treats them as noise.
  virtual uint16_t take_rx_errors() = 0;

 protected:
  ~SerialPort() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_SERIAL_PORT_H
