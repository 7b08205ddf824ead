// The simulated machine on a TCP port, as the XPort presents the real one: one connection at
// a time, bytes tunnelled to the firmware's UART. Virtual time runs as fast as it can, or in
// step with the wall clock (--realtime).
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
  bool realtime = false;
  // Fast mode never lets more machine time than this pass without a byte from a connected
  // host, so the firmware's 2 s link watchdog sees what it would on a real machine.
  uint32_t max_silent_ms = 500;
};

class SimServer {
 public:
  // Binds and listens at once (throws std::runtime_error naming the address on failure).
  SimServer(SimMachine& machine, const ServerOptions& options);
  ~SimServer();
  uint16_t port() const;
  // Serves connections until stop is set. Returns the virtual milliseconds simulated.
  uint64_t run(const std::atomic<bool>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_SIM_SERVER_H
