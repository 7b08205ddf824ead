// Datagrams the firmware sends in a scenario, recorded from the host build (TMC428 driver
// against the behavioural model through the recording fake SPI), as golden-file lines.
#ifndef HOST_SPI_SCENARIO_H
#define HOST_SPI_SCENARIO_H

#include <cstdint>  // uint32_t
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/spi/capture.h"  // Error
#include "host/spi/golden.h"   // Expected

namespace host::spi {

// One recorded datagram.
struct Exchange {
  uint32_t mosi;
  uint32_t miso;
};

// Records "init", "jog" or "job" (job_file: a drawing for the simulator). E_SCENARIO when
// the scenario is unknown or its parts are not in this build.
Error record_scenario(const std::string& name, const std::string& job_file,
                      std::vector<Exchange>* out);

// Writes the scenario as the fake SPI recorder's VCD (CS, SCK, MOSI, MISO; mode 3): what a
// logic analyser on a correct board would show, for trying out `spi decode` / `spi diff`.
Error write_scenario_vcd(const std::string& name, const std::string& job_file,
                         const std::string& path);

// Which scenarios this build can record ("init jog"), for --help.
std::string available_scenarios();

// Golden lines for recorded exchanges: MOSI exact, MISO status byte as don't-care, read data
// kept for registers the firmware wrote and wildcarded for live values (positions,
// velocities, switches, flags, chain words); runs of an identical poll collapse to {1,}.
std::vector<Expected> golden_from_exchanges(const std::vector<Exchange>& ex);

}  // namespace host::spi

#endif  // HOST_SPI_SCENARIO_H
