// Scenario recording in the host build: drivers::Tmc428 against fake::Tmc428Model through
// fake::RecordingSpi (the same parts the firmware's host tests use).
#include <fstream>  // std::ofstream

#include "firmware/config/machine_config.h"  // config::default_machine_config
#include "hal/drivers/tmc428/tmc428.h"       // drivers::Tmc428
#include "hal/fake/motion/tmc428_model.h"    // fake::Tmc428Model
#include "hal/fake/spi/recording_spi.h"      // fake::RecordingSpi
#include "hal/fake/spi/vcd_writer.h"         // fake::write_spi_vcd
#include "host/spi/scenario.h"

namespace host::spi {
namespace {

// Joystick-like jog: 1 ms ticks, each reading the positions and writing the velocities, X
// pushed right and released, Y pulled back, Z still (native TMC428 velocity units).
const int16_t kJogVelocity[][3] = {{0, 0, 0},     {40, 0, 0},    {80, -20, 0},  {120, -40, 0},
                                   {160, -60, 0}, {200, -60, 0}, {200, -60, 0}, {120, -40, 0},
                                   {40, -20, 0},  {0, 0, 0}};

// Runs a scenario; the recorder's datagrams with their times land in *out.
Error run_scenario(const std::string& name, const std::string& job_file,
                   std::vector<fake::SpiRecord>* out, fake::SpiTiming* timing) {
  out->clear();
  if (name == "job")
    return {"E_SCENARIO",
            "scenario 'job" + (job_file.empty() ? "" : " " + job_file) +
                "' needs SPI recording from the simulator (host/lib/sim does not expose "
                "its fake SPI bus yet)"};
  if (name != "init" && name != "jog")
    return {"E_SCENARIO", "unknown scenario '" + name + "' (init, jog, job FILE)"};
  const config::MachineConfig machine = config::default_machine_config();
  fake::Tmc428Model chip(machine.tmc428_clock_hz);
  fake::RecordingSpi spi(chip, machine.spi_clock_hz, machine.tmc428_clock_hz);
  drivers::Tmc428 driver(spi, machine);
  drivers::Tmc428InitResult rc = driver.init();
  if (rc != drivers::Tmc428InitResult::kOk)
    return {"E_SCENARIO",
            "driver init failed against the model, code " + std::to_string(static_cast<int>(rc))};
  *timing = spi.timing();
  if (name == "init") {
    *out = spi.records();
    return {};
  }
  spi.clear();
  for (const auto& v : kJogVelocity) {
    int32_t pos[config::kAxisCount];
    driver.read_actual_usteps(pos);
    driver.write_velocity_units(v);
    chip.advance_us(1000);
  }
  *out = spi.records();
  return {};
}

}  // namespace

std::string available_scenarios() {
  return "init jog";
}

Error record_scenario(const std::string& name, const std::string& job_file,
                      std::vector<Exchange>* out) {
  std::vector<fake::SpiRecord> records;
  fake::SpiTiming timing;
  Error e = run_scenario(name, job_file, &records, &timing);
  out->clear();
  for (const fake::SpiRecord& r : records) out->push_back({r.mosi, r.miso});
  return e;
}

Error write_scenario_vcd(const std::string& name, const std::string& job_file,
                         const std::string& path) {
  std::vector<fake::SpiRecord> records;
  fake::SpiTiming timing;
  Error e = run_scenario(name, job_file, &records, &timing);
  if (!e.ok()) return e;
  std::ofstream out(path, std::ios::binary);
  if (!out || !fake::write_spi_vcd(out, records, timing))
    return {"E_OPEN", path + ": cannot write"};
  return {};
}

}  // namespace host::spi
