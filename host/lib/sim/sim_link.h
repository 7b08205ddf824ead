// The simulated machine as a Link in the same thread: what the sender writes goes into the
// machine's UART, and a read runs machine time until the machine answers or the read's
// time-out has passed in machine time. Sender and machine move in lockstep, so nothing
// depends on how the operating system schedules threads, and machine time never waits for
// the wall clock (unless real-time pacing is asked for). The firmware's link time-outs count
// machine time here too (SimMachine::LinkTime::kMachine, unlike a SimServer's wall clock).
#ifndef HOST_LIB_SIM_SIM_LINK_H
#define HOST_LIB_SIM_SIM_LINK_H

#include <chrono>  // steady_clock
#include <string>  // std::string

#include "host/lib/sim/sim_machine.h"
#include "host/lib/stream/link.h"

namespace host::sim {

class SimLink : public Link {
 public:
  // realtime: a read that runs machine time also waits until the wall clock has caught up.
  explicit SimLink(SimMachine& machine, bool realtime = false);

  void write(const uint8_t* data, size_t size) override;
  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override;
  std::string name() const override { return "simulated machine (in process)"; }

 private:
  SimMachine& machine_;
  bool realtime_;
  std::chrono::steady_clock::time_point wall_start_;
  uint64_t machine_start_ms_;
};

// Machine time as a clock (for SenderOptions::clock): the epoch is machine time 0.
std::chrono::steady_clock::time_point machine_clock(const SimMachine& machine);

}  // namespace host::sim

#endif  // HOST_LIB_SIM_SIM_LINK_H
