// Test-side fakes for the Application's board: a serial link with a byte queue each way,
// a two-line display that remembers its text, and operator inputs set by the test.
#ifndef HOST_TESTS_APP_FAKE_BOARD_H
#define HOST_TESTS_APP_FAKE_BOARD_H

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "hal/interfaces/operator_inputs.h"
#include "hal/interfaces/serial_port.h"
#include "hal/interfaces/text_display.h"

namespace fake_app {

class FakeLink : public hal::SerialPort {
 public:
  std::deque<uint8_t> rx;   // host -> controller, not yet read
  std::vector<uint8_t> tx;  // controller -> host, not yet taken by the host
  uint16_t tx_space = 512;
  uint16_t rx_errors = 0;

  bool read_byte(uint8_t* byte) override {
    if (rx.empty()) return false;
    *byte = rx.front();
    rx.pop_front();
    return true;
  }
  uint16_t write(const uint8_t* data, uint16_t len) override {
    const uint16_t n = len < tx_space ? len : tx_space;
    tx.insert(tx.end(), data, data + n);
    return n;
  }
  uint16_t write_space() const override { return tx_space; }
  uint16_t take_rx_errors() override {
    const uint16_t n = rx_errors;
    rx_errors = 0;
    return n;
  }
};

class FakeDisplay : public hal::TextDisplay {
 public:
  std::string row[2];
  int writes = 0;
  void write_line(uint8_t r, const char* text) override {
    if (r < 2) row[r] = std::string(text).substr(0, kColumns);
    ++writes;
  }
  void clear() override { row[0].clear(), row[1].clear(); }
};

class FakeInputs : public hal::OperatorInputs {
 public:
  uint8_t bits = 0;
  uint8_t state() override { return bits; }
};

}  // namespace fake_app

#endif  // HOST_TESTS_APP_FAKE_BOARD_H
