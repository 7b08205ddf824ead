// End-to-end rig: the Application on fake board parts and the kinematic plant, driven by the
// test host, all in virtual milliseconds (tick, plant, background pass, host per ms).
#ifndef HOST_TESTS_APP_APP_RIG_H
#define HOST_TESTS_APP_APP_RIG_H

#include <cmath>
#include <vector>

#include "firmware/app/application.h"
#include "hal/fake/probe/surface_probe.h"
#include "hal/fake/spindle/fake_spindle.h"
#include "host_tests/app/fake_board.h"
#include "host_tests/app/kinematic_plant.h"
#include "host_tests/app/path_metrics.h"
#include "host_tests/app/test_host.h"

namespace fake_app {

struct AppRig {
  config::MachineConfig cfg = config::default_machine_config();
  KinematicPlant plant;
  FakeLink link;
  FakeDisplay display;
  FakeInputs inputs;
  fake::FakeSpindle spindle;
  fake::SurfaceProbe probe;  // no surface: never closes (tests set one)
  app::Application app;
  TestHost host;
  long now = 0;
  int polls_per_ms = 1;

  // link_clock: what the link's time-outs count (0: the tick, as on the controller).
  // with_probe false: a machine without a probe input.
  explicit AppRig(uint32_t seed = 1, hal::LinkClock* link_clock = nullptr, bool with_probe = true)
      : host(&link, seed) {
    app::Board b{
        &link, &plant, &display, &inputs, &spindle, link_clock, with_probe ? &probe : nullptr};
    app.init(b, cfg);
  }

  void step() {
    ++now;
    const P3 tip = position_um();
    probe.set_tool_tip_um(int32_t(std::floor(tip.x)), int32_t(std::floor(tip.y)),
                          int32_t(std::floor(tip.z)));
    app.tick_1ms();
    plant.step_1ms();
    for (int i = 0; i < polls_per_ms; ++i) app.poll();
    host.step(now);
  }
  void run(long ms) {
    for (long i = 0; i < ms; ++i) step();
  }
  template <typename Pred>
  bool run_until(Pred done, long max_ms) {
    for (long i = 0; i < max_ms; ++i) {
      step();
      if (done()) return true;
    }
    return false;
  }

  bool open_session() {
    host.open_session();
    return run_until([&] { return host.session_open; }, 2000);
  }

  // #M for all axes, then the confirm button: the current position becomes zero.
  bool zero_here() {
    host.queue(proto::ZeroingCmd{7});
    if (!run_until([&] { return app.state() == proto::MachineState::kZeroing; }, 3000))
      return false;
    run(20);
    inputs.bits = hal::kButtonConfirm;
    run(30);
    inputs.bits = 0;
    return run_until([&] { return app.zeroed() && app.state() == proto::MachineState::kIdle; },
                     3000);
  }

  // Until everything queued is acknowledged and executed and the machine stands still.
  bool run_job(long max_ms) {
    return run_until(
        [&] {
          return host.all_acked() && app.state() == proto::MachineState::kIdle &&
                 app.queue_size() == 0 && !plant.moving();
        },
        max_ms);
  }

  P3 position_um() const {
    const double k = 1000.0 / config::usteps_per_mm(cfg.axis[0]);
    return {plant.pos_usteps[0] * k, plant.pos_usteps[1] * k, plant.pos_usteps[2] * k};
  }
  std::vector<P3> recorded_um() const {
    const double k = 1000.0 / config::usteps_per_mm(cfg.axis[0]);
    std::vector<P3> out;
    for (const auto& p : plant.path) out.push_back({p[0] * k, p[1] * k, p[2] * k});
    return out;
  }
};

// A clamped cubic B-spline through a ring of n control points (an irregular closed-ish blob).
inline core::Spline blob_spline(double cx, double cy, double r, int n) {
  core::Spline s{};
  s.degree = 3;
  s.rational = false;
  s.control_count = uint16_t(n);
  s.knot_count = uint16_t(n + 4);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const double rr = r * (1.0 + 0.3 * std::sin(3 * a));
    s.control[i] = {int32_t(std::lround(cx + rr * std::cos(a))),
                    int32_t(std::lround(cy + rr * std::sin(a))), core::kWeightOneQ14};
  }
  for (int i = 0; i < n + 4; ++i) {
    s.knot[i] = i < 4 ? 0 : (i >= n ? (n - 3) * 1000 : (i - 3) * 1000);
  }
  return s;
}

// Dense double-precision points of a non-rational spline (De Boor), for error measurement.
inline std::vector<P3> dense_points(const core::Spline& s, int per_span, double z) {
  std::vector<P3> out;
  const int p = s.degree;
  for (int span = p; span < s.control_count; ++span) {
    const double t0 = s.knot[span], t1 = s.knot[span + 1];
    if (t1 <= t0) continue;
    for (int k = 0; k <= per_span; ++k) {
      const double t = t0 + (t1 - t0) * k / per_span;
      double dx[4], dy[4];
      for (int j = 0; j <= p; ++j) {
        dx[j] = s.control[span - p + j].x_um;
        dy[j] = s.control[span - p + j].y_um;
      }
      for (int r = 1; r <= p; ++r) {
        for (int j = p; j >= r; --j) {
          const int i = span - p + j;
          const double a = (t - s.knot[i]) / (s.knot[i + p - r + 1] - s.knot[i]);
          dx[j] = (1 - a) * dx[j - 1] + a * dx[j];
          dy[j] = (1 - a) * dy[j - 1] + a * dy[j];
        }
      }
      out.push_back({dx[p], dy[p], z});
    }
  }
  return out;
}

}  // namespace fake_app

#endif  // HOST_TESTS_APP_APP_RIG_H
