// The simulated machine for other programs: on a TCP port, as the XPort presents the real
// one (one connection at a time, bytes tunnelled to the firmware's UART), or on a serial
// device such as one end of a pseudo-terminal pair.
//
// The clock (docs/user-guide.md, "The simulator's clock"):
// - realtime: machine time follows the wall clock, 1 ms per ms, always.
// - fast (default): machine time runs as fast as the computer allows while the host is
//   talking: while bytes from it wait for the UART, and for fast_window_ms of machine time
//   after the last one reached the UART. After that, machine time follows the wall clock
//   until the host sends again, as a real machine's does.
// - nobody connected and nothing moving: machine time stands still (nothing would change).
// Whatever the pace, the firmware's link time-outs (the 200 ms inter-byte frame time-out,
// the 2 s link watchdog) count the wall clock of the link (SimMachine::LinkTime::kWall, set
// by the constructor): a frame may arrive in pieces up to 200 ms apart, noise does not age
// the watchdog, and 2 s without a valid frame trip it, as on the real controller.
// Machine time behind the wall clock (a busy computer) catches up, still reading the host.
#ifndef HOST_LIB_SIM_SIM_SERVER_H
#define HOST_LIB_SIM_SIM_SERVER_H

#include <atomic>   // std::atomic
#include <cstdint>  // uint16_t
#include <memory>   // std::unique_ptr
#include <string>   // std::string

#include "host/lib/sim/sim_machine.h"

namespace host::sim {

struct ServerOptions {
  std::string address = "127.0.0.1";  // loopback unless told otherwise
  uint16_t port = 10001;              // the XPort's default tunnel port; 0 = any free port
  // Serve on this serial device (a tty, or the slave end of a pty pair) instead of TCP.
  std::string device;
  bool realtime = false;
  uint32_t fast_window_ms = 500;  // see the clock rules above
};

class SimServer {
 public:
  // Binds and listens (or opens the device) at once; throws std::runtime_error naming the
  // address or device on failure.
  SimServer(SimMachine& machine, const ServerOptions& options);
  ~SimServer();
  uint16_t port() const;  // 0 when serving a device
  // Serves until stop is set. Returns the machine milliseconds simulated.
  uint64_t run(const std::atomic<bool>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_SIM_SERVER_H
