// Scenario recording when the TMC428 driver and its fakes are not in this build.
#include "host/spi/scenario.h"

namespace host::spi {

Error record_scenario(const std::string& name, const std::string&, std::vector<Exchange>*) {
  return {"E_SCENARIO", "scenario '" + name +
                            "' needs hal/drivers/tmc428, hal/fake/spi and hal/fake/motion, "
                            "which are not in this build"};
}

Error write_scenario_vcd(const std::string& name, const std::string& job_file, const std::string&) {
  std::vector<Exchange> unused;
  return record_scenario(name, job_file, &unused);
}

std::string available_scenarios() {
  return "";
}

}  // namespace host::spi
