// Scenario recording when the TMC428 driver and its fakes are not in this build.
#include "host/spi/scenario.h"

namespace host::spi {

Error record_scenario(const ScenarioRequest& request, bool, ScenarioRecording* out) {
  *out = ScenarioRecording();
  return {"E_SCENARIO", "scenario '" + request.name +
                            "' needs hal/drivers/tmc428, hal/fake/spi and hal/fake/motion, "
                            "which are not in this build"};
}

std::string available_scenarios() {
  return "";
}

}  // namespace host::spi
