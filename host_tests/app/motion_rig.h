// Test rig for the motion path alone: planner -> coordinate ring -> path controller ->
// kinematic plant, stepped in virtual milliseconds (the background loop pushes points
// between ticks like poll() would).
#ifndef HOST_TESTS_APP_MOTION_RIG_H
#define HOST_TESTS_APP_MOTION_RIG_H

#include <vector>

#include "firmware/app/axis_scaling.h"
#include "firmware/app/coordinate_ring.h"
#include "firmware/app/path_controller.h"
#include "firmware/app/planner.h"
#include "host_tests/app/kinematic_plant.h"
#include "host_tests/app/path_metrics.h"

namespace fake_app {

struct MotionRig {
  config::MachineConfig cfg = config::default_machine_config();
  KinematicPlant plant;
  app::AxisScaling scaling{};
  app::Planner planner;
  app::CoordinateRing ring;
  app::PathController controller;
  std::vector<P3> pending;  // points the "background loop" still has to push
  size_t next_pending = 0;
  uint16_t feed_um_s = 10000;
  int pushes_per_tick = 2;  // background throughput in points per ms
  uint8_t point_flags = 0;  // added to every point (kPointCurvePoint: walker points)
  long ms = 0;

  MotionRig() { setup(); }

  void setup() {
    app::build_axis_scaling(cfg, plant, &scaling);
    planner.init(scaling, app::default_planner_settings(cfg.capture_radius_um));
    controller.init(scaling);
    const int32_t origin[3] = {0, 0, 0};
    planner.set_origin(origin);
  }

  // Places the tool (and the planner origin) at p.
  void start_at(const P3& p) {
    const int32_t um[3] = {int32_t(p.x), int32_t(p.y), int32_t(p.z)};
    for (int i = 0; i < 3; ++i) plant.pos_usteps[i] = app::um_to_usteps(scaling, uint8_t(i), um[i]);
    planner.set_origin(um);
  }

  void queue(const std::vector<P3>& pts) { pending.insert(pending.end(), pts.begin(), pts.end()); }

  void background() {
    for (int k = 0; k < pushes_per_tick && next_pending < pending.size(); ++k) {
      const P3& p = pending[next_pending];
      const int32_t um[3] = {int32_t(p.x), int32_t(p.y), int32_t(p.z)};
      const uint8_t flags =
          (uint8_t)(point_flags | (next_pending + 1 == pending.size() ? app::kPointEndOfItem : 0));
      if (!planner.push(&ring, um, feed_um_s, flags, 1)) break;
      ++next_pending;
    }
  }

  void tick() {
    int32_t pos[3];
    plant.read_actual_usteps(pos);
    int16_t v[3];
    controller.tick(pos, &ring, v);
    plant.write_velocity_units(v);
    plant.step_1ms();
    ++ms;
  }

  // Runs until everything queued was pushed and the machine stands at the end (or limit).
  bool run_to_end(long max_ms) {
    for (long i = 0; i < max_ms; ++i) {
      background();
      tick();
      if (next_pending == pending.size() && controller.finished() && !plant.moving()) return true;
    }
    return false;
  }

  P3 position_um() const {
    return {plant.pos_usteps[0] * 1000.0 / config::usteps_per_mm(cfg.axis[0]),
            plant.pos_usteps[1] * 1000.0 / config::usteps_per_mm(cfg.axis[1]),
            plant.pos_usteps[2] * 1000.0 / config::usteps_per_mm(cfg.axis[2])};
  }

  std::vector<P3> recorded_um() const {
    std::vector<P3> out;
    out.reserve(plant.path.size());
    for (const auto& p : plant.path) {
      out.push_back({p[0] * 1000.0 / config::usteps_per_mm(cfg.axis[0]),
                     p[1] * 1000.0 / config::usteps_per_mm(cfg.axis[1]),
                     p[2] * 1000.0 / config::usteps_per_mm(cfg.axis[2])});
    }
    return out;
  }
};

}  // namespace fake_app

#endif  // HOST_TESTS_APP_MOTION_RIG_H
