// The path controller and the whole Application against the behavioural TMC428 model (D1's
// fake::Tmc428Model) through the real TMC428 driver: the same targets as on the plant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "firmware/app/application.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/fake/motion/tmc428_model.h"
#include "hal/fake/spi/recording_spi.h"
#include "host_tests/app/fake_board.h"
#include "host_tests/app/model_rig.h"
#include "host_tests/app/path_metrics.h"
#include "host_tests/app/test_host.h"

namespace fake_app {
namespace {

TEST(Tmc428Model, CurveSetAtTenMillimetresPerSecondMeetsErrorAndTimeTargets) {
  const std::vector<std::pair<const char*, std::vector<P3>>> curves = {
      {"circle_r20mm", circle(100000, 100000, 20000, 5)},
      {"square_40mm", square(50000, 50000, 40000)},
      {"star_5pt_r20mm", star(100000, 100000, 20000, 5)},
      {"sine_a5_p20", sine(20000, 100000, 5000, 20000, 100000, 500)},
  };
  for (const auto& c : curves) {
    ModelRig rig;
    ASSERT_TRUE(rig.setup());
    rig.start_at(c.second[0]);
    const long t0 = rig.ms;
    ASSERT_TRUE(rig.run_until_finished(200000, &c.second)) << c.first;
    const double err = max_contour_error(rig.samples, c.second);
    const double ratio = (rig.ms - t0) / (polyline_length(c.second) / 10.0);
    std::printf("[ metrics  ] TMC428 model %-16s error %5.2f um  time x%.3f\n", c.first, err,
                ratio);
    EXPECT_LE(err, 10.0) << c.first;
    EXPECT_LE(ratio, 1.10) << c.first;
    const P3 end = rig.samples.back();
    EXPECT_NEAR(end.x, c.second.back().x, 1.0) << c.first;
    EXPECT_NEAR(end.y, c.second.back().y, 1.0) << c.first;
  }
}

// A single long move at 2 mm/s on the chip model stays on its line in every direction
// (the tick's direction and axis speeds rounded down to whole micrometres and um/s leaned
// one way: 16-21 um off the line on moves like these).
TEST(Tmc428Model, LongSlowMoveStaysOnItsLineInEveryDirection) {
  double worst = 0;
  for (int deg = 5; deg < 360; deg += 25) {
    ModelRig rig;
    ASSERT_TRUE(rig.setup());
    const P3 start{110000, 110000, 0};
    rig.start_at(start);
    const double a = deg * 3.14159265358979 / 180.0;
    const P3 end{start.x + std::round(100000 * std::cos(a)),
                 start.y + std::round(100000 * std::sin(a)), 0};
    const int32_t um[3] = {int32_t(end.x), int32_t(end.y), 0};
    ASSERT_TRUE(rig.planner.push(&rig.ring, um, 2000, app::kPointEndOfItem, 1));
    ASSERT_TRUE(rig.run_until_finished(70000)) << deg;
    const double err = max_contour_error(rig.samples, {start, end});
    worst = std::max(worst, err);
    EXPECT_LE(err, 3.0) << deg << " degrees";
    EXPECT_NEAR(rig.samples.back().x, end.x, 1.0) << deg;
    EXPECT_NEAR(rig.samples.back().y, end.y, 1.0) << deg;
  }
  std::printf("[ metrics  ] TMC428 model, 100 mm at 2 mm/s: worst contour error %.2f um\n", worst);
}

TEST(Tmc428Model, ApplicationStopsOnALimitSwitchAndLatchesTheAlarm) {
  config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  chip.set_logging(false);
  fake::RecordingSpi spi(chip, 1250000);
  spi.set_recording(false);
  drivers::Tmc428 driver(spi, cfg);
  ASSERT_EQ(driver.init(), drivers::Tmc428InitResult::kOk);
  spi.set_advance_device(false);
  chip.set_switch_positions(0, -1000000, 20000 * 256 / 100);  // X right switch at 20 mm
  FakeLink link;
  FakeDisplay display;
  FakeInputs inputs;
  app::Application application;
  application.init(app::Board{&link, &driver, &display, &inputs}, cfg);
  TestHost host(&link);
  long now = 0;
  auto step = [&] {
    application.tick_1ms();
    chip.advance_us(1000);
    application.poll();
    host.step(++now);
  };
  host.open_session();
  for (int i = 0; i < 50; ++i) step();
  host.queue(proto::ZeroingCmd{7});
  for (int i = 0; i < 100; ++i) step();
  inputs.bits = hal::kButtonConfirm;
  for (int i = 0; i < 30; ++i) step();
  inputs.bits = 0;
  for (int i = 0; i < 100; ++i) step();
  ASSERT_TRUE(application.zeroed());
  host.queue(proto::FeedMoveCmd{60000, 0, 10000});
  for (int i = 0; i < 5000 && application.state() != proto::MachineState::kAlarm; ++i) step();
  EXPECT_EQ(application.state(), proto::MachineState::kAlarm);
  for (int i = 0; i < 500; ++i) step();
  const int32_t stopped = chip.x_actual(0);
  EXPECT_LT(stopped, 60000 * 256 / 100);
  for (int i = 0; i < 1000; ++i) step();
  EXPECT_EQ(chip.x_actual(0), stopped);  // nothing moves until the alarm is cleared
  ASSERT_FALSE(host.alarms.empty());
  EXPECT_EQ(host.alarms[0].alarm, proto::Alarm::kLimitSwitch);
}

// A height map loaded or cleared on a standing machine (zeroed or not, the tool in the work)
// moves no motor: the chip's positions stay and no axis gets a velocity (docs/protocol.md,
// #A). The map lies 150 um above the zero at the standing point: the old behaviour moved Z
// there on loading and plunged it back on clearing.
TEST(Tmc428Model, AHeightMapChangeMovesNoMotorOfAStandingMachine) {
  config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  chip.set_logging(false);
  fake::RecordingSpi spi(chip, 1250000);
  spi.set_recording(false);
  drivers::Tmc428 driver(spi, cfg);
  ASSERT_EQ(driver.init(), drivers::Tmc428InitResult::kOk);
  spi.set_advance_device(false);
  FakeLink link;
  FakeDisplay display;
  FakeInputs inputs;
  app::Application application;
  application.init(app::Board{&link, &driver, &display, &inputs}, cfg);
  TestHost host(&link);
  long now = 0;
  auto step = [&] {
    application.tick_1ms();
    chip.advance_us(1000);
    application.poll();
    host.step(++now);
  };
  auto settle = [&] {
    for (int i = 0; i < 20000 && !(host.all_acked() && application.queue_size() == 0 &&
                                   application.state() == proto::MachineState::kIdle);
         ++i)
      step();
    for (int i = 0; i < 300; ++i) step();
  };
  auto send_map = [&](int32_t height_um) {
    host.queue(proto::HeightMapHeaderCmd{2, 2, -50000, -50000, 60000, 60000});
    proto::HeightMapDataCmd d{};
    d.height_n = 4;
    for (int k = 0; k < 4; ++k) d.height_um[k] = height_um;
    host.queue(d);
  };
  // Every motor where it stood and still, through the frames queue() adds.
  auto expect_still = [&](const std::function<void()>& queue, const char* what) {
    settle();
    const int32_t at[3] = {chip.x_actual(0), chip.x_actual(1), chip.x_actual(2)};
    queue();
    for (int i = 0; i < 20000 && !(host.all_acked() && application.queue_size() == 0); ++i) {
      step();
      for (int m = 0; m < 3; ++m) {
        ASSERT_EQ(chip.v_actual(m), 0) << what << ": motor " << m << " moved";
        ASSERT_EQ(chip.x_actual(m), at[m]) << what << ": motor " << m;
      }
    }
    for (int i = 0; i < 300; ++i) {
      step();
      for (int m = 0; m < 3; ++m) ASSERT_EQ(chip.x_actual(m), at[m]) << what << ": motor " << m;
    }
    EXPECT_TRUE(host.errors.empty()) << what;
  };
  host.open_session();
  for (int i = 0; i < 50; ++i) step();
  ASSERT_FALSE(application.zeroed());
  expect_still([&] { send_map(150); }, "load, not zeroed");
  expect_still(
      [&] {
        host.queue(proto::HeightMapHeaderCmd{0, 0, 0, 0, 0, 0});
      },
      "clear, not zeroed");
  host.queue(proto::ZeroingCmd{7});
  for (int i = 0; i < 100; ++i) step();
  inputs.bits = hal::kButtonConfirm;
  for (int i = 0; i < 30; ++i) step();
  inputs.bits = 0;
  for (int i = 0; i < 100; ++i) step();
  ASSERT_TRUE(application.zeroed());
  host.queue(proto::ZMoveCmd{1000, 5000});
  host.queue(proto::RapidMoveCmd{5000, 5000});
  host.queue(proto::ZMoveCmd{-100, 2000});
  expect_still([&] { send_map(150); }, "load, tool down");
  const int32_t z_down = chip.x_actual(2);
  host.queue(proto::FeedMoveCmd{6000, 5000, 2000});  // follows the map: Z at -100 + 150
  settle();
  EXPECT_NEAR(std::abs(chip.x_actual(2) - z_down), 150 * 256 / 100, 8)
      << "the next move follows the new map";
  expect_still(
      [&] {
        host.queue(proto::HeightMapHeaderCmd{0, 0, 0, 0, 0, 0});
      },
      "clear, tool down");
}

}  // namespace
}  // namespace fake_app
