// Test rig for the motion path on the behavioural TMC428 model: planner -> coordinate ring ->
// path controller -> the real TMC428 driver -> fake::Tmc428Model, in virtual milliseconds,
// recording the chip's actual position after every tick.
#ifndef HOST_TESTS_APP_MODEL_RIG_H
#define HOST_TESTS_APP_MODEL_RIG_H

#include <vector>

#include "firmware/app/axis_scaling.h"
#include "firmware/app/coordinate_ring.h"
#include "firmware/app/path_controller.h"
#include "firmware/app/planner.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/fake/motion/tmc428_model.h"
#include "hal/fake/spi/recording_spi.h"
#include "host_tests/app/path_metrics.h"

namespace fake_app {

struct ModelRig {
  config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  fake::RecordingSpi spi{chip, 1250000};
  drivers::Tmc428 driver{spi, cfg};
  app::AxisScaling scaling{};
  app::Planner planner;
  app::CoordinateRing ring;
  app::PathController controller;
  std::vector<P3> samples;
  long ms = 0;

  bool setup() {
    chip.set_logging(false);
    spi.set_recording(false);
    if (driver.init() != drivers::Tmc428InitResult::kOk) return false;
    spi.set_advance_device(false);
    app::build_axis_scaling(cfg, driver, &scaling);
    planner.init(scaling, app::default_planner_settings(cfg.capture_radius_um));
    controller.init(scaling);
    return true;
  }
  void start_at(const P3& p) {
    // Drive there first (rapid), then plan from there.
    const int32_t origin[3] = {0, 0, 0};
    planner.set_origin(origin);
    const int32_t um[3] = {int32_t(p.x), int32_t(p.y), 0};
    planner.push(&ring, um, 25000, app::kPointEndOfItem, 0);
    run_until_finished(100000);
    samples.clear();
  }
  void tick() {
    int32_t pos[3];
    driver.read_actual_usteps(pos);
    int16_t v[3];
    controller.tick(pos, &ring, v);
    driver.write_velocity_units(v);
    chip.advance_us(1000);
    ++ms;
    const double k = 1000.0 / config::usteps_per_mm(cfg.axis[0]);
    samples.push_back({chip.x_actual(0) * k, chip.x_actual(1) * k, chip.x_actual(2) * k});
  }
  bool run_until_finished(long max_ms, const std::vector<P3>* pts = nullptr) {
    size_t next = 0;
    for (long i = 0; i < max_ms; ++i) {
      if (pts) {
        for (int k = 0; k < 2 && next < pts->size(); ++k) {
          const P3& p = (*pts)[next];
          const int32_t um[3] = {int32_t(p.x), int32_t(p.y), int32_t(p.z)};
          if (!planner.push(&ring, um, 10000, next + 1 == pts->size() ? app::kPointEndOfItem : 0,
                            1))
            break;
          ++next;
        }
      }
      tick();
      const bool stopped =
          chip.v_actual_q8(0) == 0 && chip.v_actual_q8(1) == 0 && chip.v_actual_q8(2) == 0;
      if ((!pts || next == pts->size()) && controller.finished() && stopped) return true;
    }
    return false;
  }
};

}  // namespace fake_app

#endif  // HOST_TESTS_APP_MODEL_RIG_H
