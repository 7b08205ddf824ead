// Scenario recording when the TMC428 driver and its fakes are not in this build.
#include "host/spi/scenario.h"

namespace host::spi {

Error record_scenario(const std::string& name, const std::string&, std::vector<Exchange>*) {
  return {"E_SCENARIO", "scenario '" + name +
                            "' needs hal/drivers/tmc428, hal/fake/spi and hal/fake/motion, "
                            "which are not in this build"};
}

std::string available_scenarios() { return ""; }

}  // namespace host::spi
