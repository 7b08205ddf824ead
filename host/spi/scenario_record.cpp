// Scenario recording in the host build: drivers::Tmc428 against fake::Tmc428Model through
// fake::RecordingSpi (the same parts the firmware's host tests use); the job scenario through
// the simulated machine (scenario_job.cpp) when host/lib/sim is in the build.
#include <sstream>  // std::ostringstream

#include "firmware/config/machine_config.h"  // config::default_machine_config
#include "hal/drivers/tmc428/tmc428.h"       // drivers::Tmc428
#include "hal/fake/motion/tmc428_model.h"    // fake::Tmc428Model
#include "hal/fake/spi/recording_spi.h"      // fake::RecordingSpi
#include "hal/fake/spi/vcd_writer.h"         // fake::write_spi_vcd
#include "host/spi/scenario.h"
#include "host/spi/scenario_job.h"  // record_job

namespace host::spi {
namespace {

// Joystick-like jog: 1 ms ticks, each reading the positions and writing the velocities, X
// pushed right and released, Y pulled back, Z still (native TMC428 velocity units).
const int16_t kJogVelocity[][3] = {{0, 0, 0},     {40, 0, 0},    {80, -20, 0},  {120, -40, 0},
                                   {160, -60, 0}, {200, -60, 0}, {200, -60, 0}, {120, -40, 0},
                                   {40, -20, 0},  {0, 0, 0}};

// Runs a scenario; the recorder's datagrams with their times land in *out.
Error run_scenario(const ScenarioRequest& request, std::vector<fake::SpiRecord>* out,
                   fake::SpiTiming* timing, std::string* note) {
  out->clear();
  (void)note;  // only a job recording has one
  const std::string& name = request.name;
  if (name == "job") {
    if (request.job_file.empty())
      return {"E_SCENARIO", "scenario 'job' needs a drawing: --scenario job FILE"};
    return record_job(request.job_file, request.max_job_datagrams, out, timing, note);
  }
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
  return "init jog job FILE";
}

Error record_scenario(const ScenarioRequest& request, bool with_vcd, ScenarioRecording* out) {
  *out = ScenarioRecording();
  std::vector<fake::SpiRecord> records;
  fake::SpiTiming timing;
  Error e = run_scenario(request, &records, &timing, &out->note);
  if (!e.ok()) return e;
  for (const fake::SpiRecord& r : records) out->exchanges.push_back({r.mosi, r.miso});
  if (with_vcd) {
    std::ostringstream vcd;
    if (!fake::write_spi_vcd(vcd, records, timing))
      return {"E_SCENARIO", "the recording cannot be written as a VCD"};
    out->vcd = vcd.str();
  }
  return {};
}

}  // namespace host::spi
