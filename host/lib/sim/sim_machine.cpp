// The simulated machine: firmware application + TMC428 driver + TMC428 model + UART timing.
#include "host/lib/sim/sim_machine.h"

#include <chrono>   // steady_clock
#include <cmath>    // std::lround
#include <cstring>  // std::memcpy

#include "firmware/app/application.h"        // app::Application, app::Board
#include "hal/drivers/tmc428/tmc428.h"       // drivers::Tmc428
#include "hal/fake/motion/tmc428_model.h"    // fake::Tmc428Model
#include "hal/fake/probe/surface_probe.h"    // fake::SurfaceProbe
#include "hal/fake/spi/recording_spi.h"      // fake::RecordingSpi
#include "hal/fake/spindle/fake_spindle.h"   // fake::FakeSpindle
#include "hal/interfaces/link_clock.h"       // hal::LinkClock
#include "hal/interfaces/operator_inputs.h"  // hal::OperatorInputs
#include "hal/interfaces/serial_port.h"      // hal::SerialPort
#include "hal/interfaces/text_display.h"     // hal::TextDisplay

namespace host::sim {

namespace {

// The firmware's UART as the application sees it: bytes already on the wire.
class SimSerial : public hal::SerialPort {
 public:
  bool read_byte(uint8_t* byte) override {
    if (rx.empty()) return false;
    *byte = rx.front();
    rx.pop_front();
    return true;
  }
  uint16_t write(const uint8_t* data, uint16_t len) override {
    const uint16_t n = std::min<uint16_t>(len, write_space());
    tx.append(data, n);
    return n;
  }
  uint16_t write_space() const override {
    return tx.size() >= kTxRing ? 0 : static_cast<uint16_t>(kTxRing - tx.size());
  }
  uint16_t take_rx_errors() override { return 0; }

  static constexpr size_t kTxRing = 128;  // as the dsPIC port's TX ring
  ByteFifo rx;                            // received, waiting for the application
  ByteFifo tx;                            // queued by the application, not sent yet
};

// A 2 x 16 display that keeps what was written.
class SimDisplay : public hal::TextDisplay {
 public:
  void write_line(uint8_t row, const char* text) override {
    if (row >= kRows) return;
    std::string line;
    for (int i = 0; i < kColumns && text[i] != '\0'; ++i) line += text[i];
    line.resize(kColumns, ' ');
    rows[row] = line;
  }
  void clear() override { rows[0] = rows[1] = std::string(kColumns, ' '); }
  std::string rows[kRows] = {std::string(kColumns, ' '), std::string(kColumns, ' ')};
};

// The firmware's link clock: machine time plus an offset, or the wall clock from an anchor.
// Switching keeps the count continuous, so a time-out running at the switch stays sane.
class SimLinkClock : public hal::LinkClock {
 public:
  explicit SimLinkClock(const uint64_t& machine_ms) : machine_ms_(machine_ms) {}
  uint16_t link_ms() override { return static_cast<uint16_t>(now_ms()); }
  uint64_t now_ms() const {
    if (!wall_) return machine_ms_ + machine_offset_ms_;
    const auto elapsed = std::chrono::steady_clock::now() - wall_anchor_;
    return wall_base_ms_ +
           static_cast<uint64_t>(
               std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count());
  }
  void set_wall(bool wall) {
    if (wall == wall_) return;
    const uint64_t at = now_ms();
    wall_ = wall;
    wall_base_ms_ = at;
    wall_anchor_ = std::chrono::steady_clock::now();
    machine_offset_ms_ = at - machine_ms_;  // unsigned: wraps as the firmware's count does
  }
  bool wall() const { return wall_; }

 private:
  const uint64_t& machine_ms_;
  bool wall_ = false;
  uint64_t machine_offset_ms_ = 0;
  uint64_t wall_base_ms_ = 0;
  std::chrono::steady_clock::time_point wall_anchor_;
};

// The operator panel: the simulated operator sets the bits.
class SimInputs : public hal::OperatorInputs {
 public:
  uint8_t state() override { return bits; }
  uint8_t bits = 0;
};

}  // namespace

struct SimMachine::Parts {
  Parts(const config::MachineConfig& cfg, const uint64_t& machine_ms)
      : chip(cfg.tmc428_clock_hz),
        spi(chip, cfg.spi_clock_hz, cfg.tmc428_clock_hz),
        driver(spi, cfg),
        link_clock(machine_ms) {}
  fake::Tmc428Model chip;
  fake::RecordingSpi spi;
  drivers::Tmc428 driver;
  SimSerial serial;
  SimDisplay display;
  SimInputs inputs;
  fake::FakeSpindle spindle;
  fake::SurfaceProbe probe;
  SimLinkClock link_clock;
  app::Application app;
  int32_t usteps_per_mm[config::kAxisCount] = {1, 1, 1};
};

SimMachine::SimMachine(const SimOptions& options)
    : options_(options), parts_(std::make_unique<Parts>(options.machine, now_ms_)) {
  Parts& p = *parts_;
  p.spi.set_recording(options.record_spi);  // minutes of traffic: off unless asked for
  p.chip.set_logging(false);
  for (int a = 0; a < config::kAxisCount; ++a) {
    const config::AxisConfig& axis = options.machine.axis[a];
    p.usteps_per_mm[a] = config::usteps_per_mm(axis);
    const int64_t margin = int64_t(options.switch_margin_um) * p.usteps_per_mm[a] / 1000;
    const int64_t travel = int64_t(axis.travel_um) * p.usteps_per_mm[a] / 1000;
    // Z travels downward from the power-on height too: its switches sit symmetric.
    const int64_t left = a == config::kAxisZ ? -travel / 2 - margin : -margin;
    const int64_t right = a == config::kAxisZ ? travel / 2 + margin : travel + margin;
    p.chip.set_switch_positions(a, static_cast<int32_t>(left), static_cast<int32_t>(right));
  }
  chip_ok_ = p.driver.init() == drivers::Tmc428InitResult::kOk;
  app::Board board;
  board.link = &p.serial;
  board.motion = &p.driver;
  board.display = &p.display;
  board.inputs = &p.inputs;
  board.spindle = &p.spindle;
  board.link_clock = &p.link_clock;
  board.probe = &p.probe;
  p.probe.set_surface(options.surface_um);
  p.app.init(board, options.machine);
  record_position();
}

SimMachine::~SimMachine() = default;

void SimMachine::from_host(const uint8_t* data, size_t size) {
  to_uart_.append(data, size);
}

std::string SimMachine::take_to_host() {
  std::string out(reinterpret_cast<const char*>(from_uart_.data()), from_uart_.size());
  from_uart_.clear();
  return out;
}

size_t SimMachine::take_to_host(uint8_t* buffer, size_t capacity) {
  const size_t n = std::min(capacity, from_uart_.size());
  if (n == 0) return 0;
  std::memcpy(buffer, from_uart_.data(), n);
  from_uart_.pop_front(n);
  return n;
}

void SimMachine::drop_link_bytes() {
  Parts& p = *parts_;
  to_uart_.clear();
  p.serial.rx.clear();
  p.serial.tx.clear();
  from_uart_.clear();
}

void SimMachine::set_link_time(LinkTime time) {
  parts_->link_clock.set_wall(time == LinkTime::kWall);
}

SimMachine::LinkTime SimMachine::link_time() const {
  return parts_->link_clock.wall() ? LinkTime::kWall : LinkTime::kMachine;
}

bool SimMachine::busy() const {
  const Parts& p = *parts_;
  for (int a = 0; a < config::kAxisCount; ++a) {
    if (p.chip.v_actual_q8(a) != 0) return true;
  }
  return !to_uart_.empty() || !p.serial.rx.empty() || !p.serial.tx.empty();
}

// The simulated operator: confirms zeroing where the tool stands, as a person would after
// jogging to the corner of the board, and confirms each pause after pause_confirm_ms.
void SimMachine::operate_panel() {
  Parts& p = *parts_;
  if (confirm_hold_ms_ > 0) {
    p.inputs.bits = hal::kButtonConfirm;
    if (--confirm_hold_ms_ == 0) p.inputs.bits = 0;
    return;
  }
  const int kPressMs = 50;  // well past the debounce
  const proto::MachineState state = p.app.state();
  if (state == proto::MachineState::kZeroing && options_.auto_zero) confirm_hold_ms_ = kPressMs;
  if (state != proto::MachineState::kPaused || options_.pause_confirm_ms < 0) {
    paused_ms_ = 0;
    return;
  }
  if (++paused_ms_ >= options_.pause_confirm_ms) {
    confirm_hold_ms_ = kPressMs;
    paused_ms_ = 0;
    ++pauses_confirmed_;
  }
}

bool SimMachine::spindle_on() const {
  return parts_->spindle.on();
}

int SimMachine::spindle_switches() const {
  return parts_->spindle.switches();
}

void SimMachine::set_surface(std::function<int32_t(int32_t x_um, int32_t y_um)> surface_um) {
  parts_->probe.set_surface(std::move(surface_um));
}

bool SimMachine::probe_closed() const {
  return parts_->app.probe_closed();
}

void SimMachine::record_position() {
  const ToolSample s = position();
  if (have_sample_ && last_sample_.x_mm == s.x_mm && last_sample_.y_mm == s.y_mm &&
      last_sample_.z_mm == s.z_mm)
    return;
  last_sample_ = s;
  have_sample_ = true;
  if (sink_)
    sink_(s);
  else
    trace_.push_back(s);
}

ToolSample SimMachine::position() const {
  const Parts& p = *parts_;
  ToolSample s;
  s.t_ms = now_ms_;
  s.x_mm = double(p.chip.x_actual(0)) / p.usteps_per_mm[0];
  s.y_mm = double(p.chip.x_actual(1)) / p.usteps_per_mm[1];
  s.z_mm = double(p.chip.x_actual(2)) / p.usteps_per_mm[2];
  return s;
}

void SimMachine::step_ms() {
  Parts& p = *parts_;
  const double bytes_per_ms = options_.baud / 10.0 / 1000.0;
  rx_credit_ = std::min(rx_credit_ + bytes_per_ms, 4.0 + bytes_per_ms);  // 4-byte UART FIFO
  // A byte per whole credit while bytes wait, moved as one run (the credit, below 16, loses
  // nothing to subtracting a whole number at once: the same as a byte at a time).
  if (rx_credit_ >= 1.0 && !to_uart_.empty()) {
    const size_t n = std::min(static_cast<size_t>(rx_credit_), to_uart_.size());
    p.serial.rx.append(to_uart_.data(), n);
    to_uart_.pop_front(n);
    rx_credit_ -= static_cast<double>(n);
    last_host_byte_ms_ = now_ms_ + 1;
  }
  ++now_ms_;
  p.chip.advance_to_ns(now_ms_ * 1000000ull);
  operate_panel();
  // The tool tip for the probe input, which reads it only against a surface (without one it
  // stays open, or forced): no board, no reading the model, whose motors then integrate
  // when the firmware next reads or changes them (lazily, to the same result).
  if (p.probe.has_surface()) {
    int32_t tip_um[config::kAxisCount];
    for (int a = 0; a < config::kAxisCount; ++a)
      tip_um[a] = static_cast<int32_t>(int64_t(p.chip.x_actual(a)) * 1000 / p.usteps_per_mm[a]);
    p.probe.set_tool_tip_um(tip_um[0], tip_um[1], tip_um[2]);
  }
  p.app.tick_1ms();
  p.app.poll();
  tx_credit_ = std::min(tx_credit_ + bytes_per_ms, 4.0 + bytes_per_ms);
  if (tx_credit_ >= 1.0 && !p.serial.tx.empty()) {
    const size_t n = std::min(static_cast<size_t>(tx_credit_), p.serial.tx.size());
    from_uart_.append(p.serial.tx.data(), n);
    p.serial.tx.pop_front(n);
    tx_credit_ -= static_cast<double>(n);
  }
  record_position();
}

void SimMachine::set_spi_recording(bool on) {
  parts_->spi.set_recording(on);
}

const std::vector<fake::SpiRecord>& SimMachine::spi_records() const {
  return parts_->spi.records();
}

const fake::SpiTiming& SimMachine::spi_timing() const {
  return parts_->spi.timing();
}

std::string SimMachine::lcd_line(int row) const {
  return row >= 0 && row < 2 ? parts_->display.rows[row] : std::string();
}

}  // namespace host::sim
