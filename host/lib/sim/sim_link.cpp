// In-process lockstep link to the simulated machine (see sim_link.h).
#include "host/lib/sim/sim_link.h"

#include <algorithm>  // std::min
#include <thread>     // sleep_until

namespace host::sim {

SimLink::SimLink(SimMachine& machine, bool realtime)
    : machine_(machine),
      realtime_(realtime),
      wall_start_(std::chrono::steady_clock::now()),
      machine_start_ms_(machine.now_ms()) {}

void SimLink::write(const uint8_t* data, size_t size) {
  machine_.from_host(data, size);
}

size_t SimLink::read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) {
  const uint64_t until_ms = machine_.now_ms() + static_cast<uint64_t>(std::max<long>(
                                                    0, static_cast<long>(timeout.count())));
  // Bytes not taken by an earlier read come first, without running machine time; they
  // wait in the machine (no copy a millisecond through a string).
  while (!machine_.to_host_waiting() && machine_.now_ms() < until_ms) {
    machine_.step_ms();
    if (realtime_) {
      std::this_thread::sleep_until(
          wall_start_ + std::chrono::milliseconds(machine_.now_ms() - machine_start_ms_));
    }
  }
  return machine_.take_to_host(buffer, capacity);
}

std::chrono::steady_clock::time_point machine_clock(const SimMachine& machine) {
  return std::chrono::steady_clock::time_point(std::chrono::milliseconds(machine.now_ms()));
}

}  // namespace host::sim
