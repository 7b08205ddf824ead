// The simulated machine: the firmware application built for the host, wired to the TMC428
// behavioural model through the real TMC428 driver, a UART at 115200 Bd in virtual time,
// a captured LCD and a simulated operator. Time advances one millisecond per step.
#ifndef HOST_LIB_SIM_SIM_MACHINE_H
#define HOST_LIB_SIM_SIM_MACHINE_H

#include <cstdint>     // uint8_t
#include <functional>  // std::function
#include <memory>      // std::unique_ptr
#include <string>      // std::string
#include <vector>      // std::vector

#include "firmware/config/machine_config.h"
#include "host/lib/sim/byte_fifo.h"

namespace fake {
struct SpiRecord;  // hal/fake/spi/spi_record.h
struct SpiTiming;
}  // namespace fake

namespace host::sim {

struct SimOptions {
  config::MachineConfig machine = config::default_machine_config();
  uint32_t baud = 115200;  // 10 bits a byte on the wire (8N1)
  bool auto_zero = true;   // the simulated operator confirms zeroing where the tool stands
  // The simulated operator presses confirm this long after a #P pause began (< 0: never).
  int pause_confirm_ms = 1000;
  // Limit switches this far beyond each end of the travel from the power-on position.
  int32_t switch_margin_um = 5000;
  // Record every SPI datagram from power-on (the TMC428 init included); off by default:
  // a minute of motion is ~420 000 datagrams. set_spi_recording() switches it later.
  bool record_spi = false;
  // The blank's top surface: the Z (um) of the copper at a machine X/Y (um), in the frame of
  // position() x 1000. The simulated probe input closes where the tool tip reaches it (#Y).
  // Empty: no board, the probe never closes.
  std::function<int32_t(int32_t x_um, int32_t y_um)> surface_um;
};

// One sample of the tool position (from the model's x_actual), when it moved.
struct ToolSample {
  uint64_t t_ms;
  double x_mm, y_mm, z_mm;
};

class SimMachine {
 public:
  explicit SimMachine(const SimOptions& options);
  ~SimMachine();
  SimMachine(const SimMachine&) = delete;
  SimMachine& operator=(const SimMachine&) = delete;

  // Bytes from the PC; they reach the firmware's UART at the baud rate.
  void from_host(const uint8_t* data, size_t size);
  // Bytes the firmware sent that have left its UART by now.
  std::string take_to_host();
  // The same into buffer, at most capacity of them (the rest stay for the next take): no
  // string a call (SimLink takes them every simulated millisecond).
  size_t take_to_host(uint8_t* buffer, size_t capacity);
  bool to_host_waiting() const { return !from_uart_.empty(); }
  // The host's connection is gone (or a new one starts): what it sent that the firmware has
  // not read yet, and the replies nobody has taken, are dropped. Frames the firmware had
  // already taken stay taken, as on a lost link.
  void drop_link_bytes();

  // One millisecond: UART bytes, model time, the 1 ms tick, a background-loop pass.
  void step_ms();
  uint64_t now_ms() const { return now_ms_; }

  // What the firmware's link time-outs count (hal::LinkClock: the 200 ms inter-byte frame
  // time-out, the 2 s link watchdog). kMachine (the default): machine time, for a client in
  // lockstep with it (SimLink). kWall: the wall clock, for another program on a socket
  // (SimServer), as the real controller sees its link however fast machine time runs between
  // the bytes. A switch continues the count from where it stood.
  enum class LinkTime { kMachine, kWall };
  void set_link_time(LinkTime time);
  LinkTime link_time() const;

  // True while the axes move or bytes wait in either UART direction.
  bool busy() const;
  // Bytes from the PC that have not reached the firmware's UART yet.
  bool host_bytes_waiting() const { return !to_uart_.empty(); }
  // Machine time the newest byte from the PC reached the firmware's UART (0: none yet).
  uint64_t last_host_byte_ms() const { return last_host_byte_ms_; }
  // Whether the TMC428 driver's self-check passed at power-on (else the app is in alarm).
  bool chip_ok() const { return chip_ok_; }
  // Every tool position change, one sample per millisecond at most: kept in trace() unless a
  // sink takes them (then nothing is stored: long jobs record in bounded memory).
  const std::vector<ToolSample>& trace() const { return trace_; }
  void set_sample_sink(std::function<void(const ToolSample&)> sink) { sink_ = std::move(sink); }
  std::string lcd_line(int row) const;
  // #P pauses the simulated operator confirmed; the spindle output and its switchings.
  int pauses_confirmed() const { return pauses_confirmed_; }
  bool spindle_on() const;
  int spindle_switches() const;
  // Replaces SimOptions::surface_um (a new blank; empty: none).
  void set_surface(std::function<int32_t(int32_t x_um, int32_t y_um)> surface_um);
  // The probe input as the firmware reads it now (the tool tip on or in the surface).
  bool probe_closed() const;
  // The firmware's tool position in mm (model x_actual / microsteps per mm).
  ToolSample position() const;

  // SPI datagrams between the TMC428 driver and the model (time, MOSI, MISO), recorded
  // while recording is on (SimOptions::record_spi, set_spi_recording).
  void set_spi_recording(bool on);
  const std::vector<fake::SpiRecord>& spi_records() const;
  // The bus timing of the records (for fake::write_spi_vcd).
  const fake::SpiTiming& spi_timing() const;

 private:
  struct Parts;
  void operate_panel();
  void record_position();

  SimOptions options_;
  std::unique_ptr<Parts> parts_;
  uint64_t now_ms_ = 0;
  double rx_credit_ = 0, tx_credit_ = 0;  // bytes the UART may move this ms
  ByteFifo to_uart_;                      // PC -> firmware, not on the wire yet
  uint64_t last_host_byte_ms_ = 0;
  ByteFifo from_uart_;  // firmware -> PC, delivered
  std::vector<ToolSample> trace_;
  std::function<void(const ToolSample&)> sink_;
  ToolSample last_sample_{};
  bool have_sample_ = false;
  bool chip_ok_ = false;
  int confirm_hold_ms_ = 0;
  int paused_ms_ = 0;  // how long the current pause has waited for the operator
  int pauses_confirmed_ = 0;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_SIM_MACHINE_H
