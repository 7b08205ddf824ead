// In-process lockstep link to the simulated machine (see sim_link.h).
#include "host/lib/sim/sim_link.h"

#include <algorithm>  // std::min
#include <cstring>    // std::memcpy
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
  while (pending_at_ == pending_.size()) {
    pending_ = machine_.take_to_host();
    pending_at_ = 0;
    if (!pending_.empty() || machine_.now_ms() >= until_ms) break;
    machine_.step_ms();
    if (realtime_) {
      std::this_thread::sleep_until(
          wall_start_ + std::chrono::milliseconds(machine_.now_ms() - machine_start_ms_));
    }
  }
  const size_t n = std::min(capacity, pending_.size() - pending_at_);
  if (n > 0) std::memcpy(buffer, pending_.data() + pending_at_, n);
  pending_at_ += n;
  return n;
}

std::chrono::steady_clock::time_point machine_clock(const SimMachine& machine) {
  return std::chrono::steady_clock::time_point(std::chrono::milliseconds(machine.now_ms()));
}

}  // namespace host::sim
