// The TMC246 status check in the 1 ms tick: the TMC428 driver's one-datagram-per-step
// poll_driver_check() against the behavioural chip model (fake::Tmc428Model), and the
// Application raising kDriverFault / kPowerLost from it.
#include <gtest/gtest.h>

#include "firmware/app/application.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/fake/motion/tmc428_model.h"
#include "hal/fake/spi/recording_spi.h"
#include "host_tests/app/fake_board.h"
#include "host_tests/app/test_host.h"

namespace fake_app {
namespace {

const uint16_t kHealthy = fake::Tmc428Model::kTmc246StatusDefault;  // 0xF00
const uint16_t kOvertemperature = 0x80;
const uint16_t kUndervoltage = 0x20;
const uint16_t kOpenLoadBoth = 0x0C;

// The driver on the model, polled as the tick does: one step every 10 ms of chip time.
struct DriverRig {
  config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  fake::RecordingSpi spi{chip, 1250000};
  drivers::Tmc428 driver{spi, cfg};
  uint32_t most_datagrams_per_step = 0;

  bool setup() {
    chip.set_logging(false);
    spi.set_recording(false);
    if (driver.init() != drivers::Tmc428InitResult::kOk) return false;
    spi.set_advance_device(false);
    return true;
  }
  // Steps until a result other than pending (at most max_steps); returns it.
  uint8_t first_result(int max_steps) {
    for (int i = 0; i < max_steps; ++i) {
      const uint32_t before = spi.transfers();
      const uint8_t r = driver.poll_driver_check();
      if (spi.transfers() - before > most_datagrams_per_step)
        most_datagrams_per_step = spi.transfers() - before;
      chip.advance_us(10000);
      if (r != hal::kDriverCheckPending) return r;
    }
    return hal::kDriverCheckPending;
  }
};

TEST(Tmc428DriverCheck, HealthyDriversReportOkUsingAtMostOneDatagramPerStep) {
  DriverRig rig;
  ASSERT_TRUE(rig.setup());
  EXPECT_EQ(rig.first_result(100), hal::kDriverCheckOk);
  EXPECT_EQ(rig.first_result(100), hal::kDriverCheckOk);  // and again after re-arming
  EXPECT_LE(rig.most_datagrams_per_step, 1u);
}

TEST(Tmc428DriverCheck, OvertemperatureOnOneDriverIsAFault) {
  DriverRig rig;
  ASSERT_TRUE(rig.setup());
  rig.chip.set_driver_status(1, kHealthy | kOvertemperature);
  EXPECT_EQ(rig.first_result(100), hal::kDriverCheckFault);
  EXPECT_EQ(rig.driver.driver_status(1), kHealthy | kOvertemperature);
  EXPECT_EQ(rig.driver.driver_status(0), kHealthy);
}

TEST(Tmc428DriverCheck, UndervoltageIsReportedAsUndervoltage) {
  DriverRig rig;
  ASSERT_TRUE(rig.setup());
  rig.chip.set_driver_status(2, kHealthy | kUndervoltage);
  EXPECT_EQ(rig.first_result(100), hal::kDriverCheckUndervoltage);
}

TEST(Tmc428DriverCheck, OpenLoadFlagsAloneAreNoFault) {
  DriverRig rig;
  ASSERT_TRUE(rig.setup());
  rig.chip.set_driver_status(0, kHealthy | kOpenLoadBoth);
  EXPECT_EQ(rig.first_result(100), hal::kDriverCheckOk);
}

TEST(Tmc428DriverCheck, ChainReturnLineStuckLowIsAFault) {
  DriverRig rig;
  ASSERT_TRUE(rig.setup());
  rig.chip.set_chain_sdi_stuck(0);  // every status word 0: the always-1 bit 8 is missing
  EXPECT_EQ(rig.first_result(100), hal::kDriverCheckFault);
}

TEST(Tmc428DriverCheck, EachOvercurrentFlagIsAFault) {
  for (uint16_t flag : {0x10, 0x02, 0x01}) {  // OCHS, OCB, OCA
    EXPECT_EQ(drivers::Tmc428::classify_driver_status(kHealthy | flag), hal::kDriverCheckFault)
        << flag;
  }
}

// The whole Application on the model: zeroed, running a job, then a driver reports status.
struct AppOnModel {
  config::MachineConfig cfg = config::default_machine_config();
  fake::Tmc428Model chip;
  fake::RecordingSpi spi{chip, 1250000};
  drivers::Tmc428 driver{spi, cfg};
  FakeLink link;
  FakeDisplay display;
  FakeInputs inputs;
  app::Application application;
  TestHost host{&link};
  long now = 0;

  void step(int n = 1) {
    for (int i = 0; i < n; ++i) {
      application.tick_1ms();
      chip.advance_us(1000);
      application.poll();
      host.step(++now);
    }
  }
  bool setup_and_start_a_job() {
    chip.set_logging(false);
    spi.set_recording(false);
    if (driver.init() != drivers::Tmc428InitResult::kOk) return false;
    spi.set_advance_device(false);
    application.init(app::Board{&link, &driver, &display, &inputs}, cfg);
    host.open_session();
    step(50);
    host.queue(proto::ZeroingCmd{7});
    step(100);
    inputs.bits = hal::kButtonConfirm;
    step(30);
    inputs.bits = 0;
    step(100);
    if (!application.zeroed()) return false;
    host.queue(proto::FeedMoveCmd{60000, 0, 10000});
    step(500);
    return application.state() == proto::MachineState::kRunning;
  }
  // Steps until the alarm state (at most max_ms); true if reached.
  bool run_until_alarm(int max_ms) {
    for (int i = 0; i < max_ms; ++i) {
      step();
      if (application.state() == proto::MachineState::kAlarm) return true;
    }
    return false;
  }
};

TEST(AppDriverCheck, OvertemperatureMidJobStopsTheMachineWithDriverFault) {
  AppOnModel rig;
  ASSERT_TRUE(rig.setup_and_start_a_job());
  rig.chip.set_driver_status(0, kHealthy | kOvertemperature);
  ASSERT_TRUE(rig.run_until_alarm(500));
  EXPECT_EQ(rig.application.alarm(), proto::Alarm::kDriverFault);
  rig.step(500);
  const int32_t stopped = rig.chip.x_actual(0);
  rig.step(1000);
  EXPECT_EQ(rig.chip.x_actual(0), stopped);  // nothing moves until the alarm is cleared
  ASSERT_FALSE(rig.host.alarms.empty());
  EXPECT_EQ(rig.host.alarms[0].alarm, proto::Alarm::kDriverFault);
  EXPECT_FALSE(rig.application.zeroed());  // a driver that switched off lost steps
}

TEST(AppDriverCheck, UndervoltageMidJobIsPowerLost) {
  AppOnModel rig;
  ASSERT_TRUE(rig.setup_and_start_a_job());
  rig.chip.set_driver_status(2, kHealthy | kUndervoltage);
  ASSERT_TRUE(rig.run_until_alarm(500));
  EXPECT_EQ(rig.application.alarm(), proto::Alarm::kPowerLost);
}

TEST(AppDriverCheck, HealthyDriversRaiseNoAlarmDuringAJob) {
  AppOnModel rig;
  ASSERT_TRUE(rig.setup_and_start_a_job());
  EXPECT_FALSE(rig.run_until_alarm(2000));
  EXPECT_EQ(rig.application.alarm(), proto::Alarm::kNone);
}

}  // namespace
}  // namespace fake_app
