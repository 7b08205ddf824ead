// A simulated machine (default options) on any free loopback port, served from a thread
// while the object lives: the start of most of the simulator's link tests.
#ifndef HOST_TESTS_HOST_SIM_SERVED_SIM_H
#define HOST_TESTS_HOST_SIM_SERVED_SIM_H

#include <cstdint>  // uint16_t
#include <string>   // std::string

#include "host/lib/sim/sim_machine.h"
#include "host/lib/sim/sim_server.h"
#include "host_tests/host/sim/sim_test_jobs.h"  // Serving

namespace host::test {

inline sim::ServerOptions any_loopback_port() {
  sim::ServerOptions so;
  so.port = 0;
  return so;
}

class ServedSim {
 public:
  ServedSim() : server(machine, any_loopback_port()), serving_(server) {}
  uint16_t port() const { return server.port(); }
  std::string address() const { return "tcp://127.0.0.1:" + std::to_string(server.port()); }
  // Ends the serving (joins its thread) before the test reads the machine's state.
  void stop() { serving_.stop(); }

  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimServer server;

 private:
  Serving serving_;
};

}  // namespace host::test

#endif  // HOST_TESTS_HOST_SIM_SERVED_SIM_H
