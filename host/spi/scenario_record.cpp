// Scenario recording in the host build: drivers::Tmc428 against fake::Tmc428Model through
// fake::RecordingSpi (the same parts the firmware's host tests use).
#include "firmware/config/machine_config.h"  // config::default_machine_config
#include "hal/drivers/tmc428/tmc428.h"       // drivers::Tmc428
#include "hal/fake/motion/tmc428_model.h"    // fake::Tmc428Model
#include "hal/fake/spi/recording_spi.h"      // fake::RecordingSpi
#include "host/spi/scenario.h"

namespace host::spi {
namespace {

// Joystick-like jog: 1 ms ticks, each reading the positions and writing the velocities, X
// pushed right and released, Y pulled back, Z still (native TMC428 velocity units).
const int16_t kJogVelocity[][3] = {{0, 0, 0},       {40, 0, 0},     {80, -20, 0},
                                   {120, -40, 0},   {160, -60, 0},  {200, -60, 0},
                                   {200, -60, 0},   {120, -40, 0},  {40, -20, 0},
                                   {0, 0, 0}};

void copy_records(const fake::RecordingSpi& spi, std::vector<Exchange>* out) {
  for (const fake::SpiRecord& r : spi.records()) out->push_back({r.mosi, r.miso});
}

}  // namespace

std::string available_scenarios() { return "init jog"; }

Error record_scenario(const std::string& name, const std::string& job_file,
                      std::vector<Exchange>* out) {
  out->clear();
  if (name == "job")
    return {"E_SCENARIO", "scenario 'job" + (job_file.empty() ? "" : " " + job_file) +
                              "' needs the simulator (host/sim), which is not in this build"};
  if (name != "init" && name != "jog")
    return {"E_SCENARIO", "unknown scenario '" + name + "' (init, jog, job FILE)"};
  const config::MachineConfig machine = config::default_machine_config();
  fake::Tmc428Model chip(machine.tmc428_clock_hz);
  fake::RecordingSpi spi(chip, machine.spi_clock_hz, machine.tmc428_clock_hz);
  drivers::Tmc428 driver(spi, machine);
  drivers::Tmc428InitResult rc = driver.init();
  if (rc != drivers::Tmc428InitResult::kOk)
    return {"E_SCENARIO", "driver init failed against the model, code " +
                              std::to_string(static_cast<int>(rc))};
  if (name == "init") {
    copy_records(spi, out);
    return {};
  }
  spi.clear();
  for (const auto& v : kJogVelocity) {
    int32_t pos[config::kAxisCount];
    driver.read_actual_usteps(pos);
    driver.write_velocity_units(v);
    chip.advance_us(1000);
  }
  copy_records(spi, out);
  return {};
}

}  // namespace host::spi
