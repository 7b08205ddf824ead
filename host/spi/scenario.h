// Datagrams the firmware sends in a scenario, recorded from the host build (TMC428 driver
// against the behavioural model through the recording fake SPI), as golden-file lines.
#ifndef HOST_SPI_SCENARIO_H
#define HOST_SPI_SCENARIO_H

#include <cstddef>  // size_t
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

// Datagrams of a job kept after the init by default: ~0.3 s of the 1 ms loop (7 a tick).
const size_t kDefaultJobDatagrams = 2000;

// What to record: "init", "jog" or "job" (job_file: a drawing for the simulator).
struct ScenarioRequest {
  std::string name = "init";
  std::string job_file;
  size_t max_job_datagrams = kDefaultJobDatagrams;  // after the init; 0 = the whole job
};

struct ScenarioRecording {
  std::vector<Exchange> exchanges;
  std::string note;  // how a job recording ended ("" for init and jog)
  std::string vcd;   // the fake SPI recorder's VCD of the same datagrams, when asked for
};

// Records a scenario once; with_vcd also renders it as a VCD (CS, SCK, MOSI, MISO; mode 3):
// what a logic analyser on a correct board would show. E_SCENARIO when the scenario is
// unknown or its parts are not in this build, E_OPEN when the drawing cannot be read.
Error record_scenario(const ScenarioRequest& request, bool with_vcd, ScenarioRecording* out);

// Shorthands: the datagrams only (default bound), and the VCD written to a file.
Error record_scenario(const std::string& name, const std::string& job_file,
                      std::vector<Exchange>* out);
Error write_scenario_vcd(const std::string& name, const std::string& job_file,
                         const std::string& path);

// Which scenarios this build can record ("init jog job FILE"), for --help.
std::string available_scenarios();

// Golden lines for recorded exchanges: MOSI exact, MISO status byte as don't-care, read data
// kept for registers the firmware wrote and wildcarded for live values (positions,
// velocities, switches, flags, chain words); runs of an identical poll collapse to {1,}.
std::vector<Expected> golden_from_exchanges(const std::vector<Exchange>& ex);

}  // namespace host::spi

#endif  // HOST_SPI_SCENARIO_H
