// The in-process lockstep link to a simulated machine, cut (no byte either way) for a while:
// a network that freezes and comes back. The sender's reads still run machine time while it
// is cut, so the machine's link watchdog (2 s without a valid frame) sees the silence.
#pragma once

#include <chrono>   // std::chrono
#include <cstdint>  // uint64_t
#include <string>   // std::string

#include "host/lib/sim/sim_link.h"

namespace host::test {

class CutLink : public Link {
 public:
  explicit CutLink(sim::SimMachine& m) : machine_(m), inner_(m) {}
  // From now (machine time) for cut_ms.
  void cut_for(uint32_t cut_ms) { cut_until_ms_ = now_ms() + cut_ms; }
  bool cut() const { return now_ms() < cut_until_ms_; }
  void write(const uint8_t* data, size_t size) override {
    if (!cut()) inner_.write(data, size);
  }
  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    const bool was_cut = cut();
    const size_t n = inner_.read(buffer, capacity, timeout);
    return was_cut ? 0 : n;  // a reply sent while cut never arrives
  }
  std::string name() const override { return "cut link"; }

 private:
  uint64_t now_ms() const {
    return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                     sim::machine_clock(machine_).time_since_epoch())
                                     .count());
  }
  sim::SimMachine& machine_;
  sim::SimLink inner_;
  uint64_t cut_until_ms_ = 0;
};

}  // namespace host::test
