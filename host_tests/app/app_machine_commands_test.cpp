// The machine commands through the Application: operator pause (#P), dwell (#W), spindle
// (#N) and drilling (#L), on the kinematic plant with the fake panel and spindle output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "host_tests/app/app_rig.h"

namespace fake_app {
namespace {

using proto::ErrorCode;
using proto::MachineState;

bool has_error(const TestHost& h, ErrorCode code) {
  for (const auto& e : h.errors) {
    if (e.code == code) return true;
  }
  return false;
}

proto::PauseCmd pause_text(const char* text) {
  proto::PauseCmd p{};
  p.length = static_cast<uint8_t>(std::strlen(text));
  std::memcpy(p.text, text, p.length);
  return p;
}

// A zeroed machine with an open session.
struct Ready : AppRig {
  Ready() {
    EXPECT_TRUE(open_session());
    EXPECT_TRUE(zero_here());
  }
  void press_confirm() {
    inputs.bits = hal::kButtonConfirm;
    run(30);
    inputs.bits = 0;
  }
};

TEST(AppPause, WaitsAtAStandstillShowingItsTextUntilConfirmIsPressed) {
  Ready rig;
  rig.host.queue(proto::FeedMoveCmd{10000, 0, 10000});
  rig.host.queue(pause_text("CHANGE TO T2"));
  rig.host.queue(proto::FeedMoveCmd{10000, 8000, 10000});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kPaused; }, 10000));
  // The move before the pause is finished, the one after it has not started.
  EXPECT_NEAR(rig.position_um().x, 10000, 1.0);
  EXPECT_NEAR(rig.position_um().y, 0, 1.0);
  rig.run(3000);  // an operator takes their time; the link watchdog must not mind
  EXPECT_EQ(rig.app.state(), MachineState::kPaused);
  EXPECT_FALSE(rig.plant.moving());
  EXPECT_NEAR(rig.position_um().y, 0, 1.0);
  EXPECT_EQ(rig.display.row[0], "CHANGE TO T2");
  EXPECT_EQ(rig.display.row[1], "CONFIRM TO GO ON");
  rig.host.query_status();
  rig.run(20);
  EXPECT_EQ(rig.host.status.state, MachineState::kPaused);
  EXPECT_EQ(rig.host.status.flags & proto::kStatusLinkHold, 0);

  rig.press_confirm();
  ASSERT_TRUE(rig.run_job(10000));
  EXPECT_NEAR(rig.position_um().y, 8000, 1.0);
  EXPECT_TRUE(rig.host.errors.empty());
}

TEST(AppPause, AButtonAlreadyHeldWhenThePauseStartsDoesNotConfirmIt) {
  Ready rig;
  rig.inputs.bits = hal::kButtonConfirm;  // held down since before the pause
  rig.host.queue(pause_text(""));
  rig.host.queue(proto::FeedMoveCmd{0, 5000, 10000});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kPaused; }, 5000));
  rig.run(500);
  EXPECT_EQ(rig.app.state(), MachineState::kPaused);
  EXPECT_EQ(rig.display.row[0], "PAUSED");
  rig.inputs.bits = 0;
  rig.run(50);
  EXPECT_EQ(rig.app.state(), MachineState::kPaused);  // releasing is not confirming
  rig.press_confirm();
  ASSERT_TRUE(rig.run_job(10000));
  EXPECT_NEAR(rig.position_um().y, 5000, 1.0);
}

TEST(AppPause, AbortEndsThePauseWithTheJob) {
  Ready rig;
  rig.host.queue(pause_text("WAIT"));
  rig.host.queue(proto::FeedMoveCmd{0, 5000, 10000});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kPaused; }, 5000));
  rig.host.send_realtime(proto::AbortCmd{});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kIdle; }, 3000));
  rig.press_confirm();
  rig.run(500);
  EXPECT_NEAR(rig.position_um().y, 0, 1.0);  // the move after the pause never ran
}

TEST(AppDwell, HoldsEveryAxisStillForItsTime) {
  Ready rig;
  rig.host.queue(proto::FeedMoveCmd{5000, 0, 10000});
  rig.host.queue(proto::DwellCmd{700});
  rig.host.queue(proto::FeedMoveCmd{5000, 5000, 10000});
  long arrived = -1, left = -1;
  ASSERT_TRUE(rig.run_until(
      [&] {
        const P3 p = rig.position_um();
        if (arrived < 0 && std::abs(p.x - 5000) < 1.0 && !rig.plant.moving()) arrived = rig.now;
        if (arrived >= 0 && left < 0 && p.y > 1.0) left = rig.now;
        return left >= 0;
      },
      10000));
  const long still_ms = left - arrived;
  std::printf("[ metrics  ] dwell 700 ms: axes still for %ld ms\n", still_ms);
  EXPECT_GE(still_ms, 700);
  EXPECT_LE(still_ms, 760);
  ASSERT_TRUE(rig.run_job(10000));
  EXPECT_NEAR(rig.position_um().y, 5000, 1.0);
}

TEST(AppSpindle, SwitchesOnlyOnceTheMovesBeforeItHaveFinished) {
  Ready rig;
  rig.host.queue(proto::FeedMoveCmd{20000, 0, 10000});
  rig.host.queue(proto::SpindleCmd{1});
  rig.host.queue(proto::FeedMoveCmd{20000, 5000, 10000});
  rig.host.queue(proto::SpindleCmd{0});
  double x_when_on = -1;
  bool seen_on = false;
  ASSERT_TRUE(rig.run_until(
      [&] {
        if (rig.spindle.on() && !seen_on) {
          seen_on = true;
          x_when_on = rig.position_um().x;
        }
        return rig.host.all_acked() && rig.app.state() == MachineState::kIdle &&
               rig.app.queue_size() == 0 && !rig.plant.moving();
      },
      20000));
  EXPECT_TRUE(seen_on);
  EXPECT_NEAR(x_when_on, 20000, 1.0);
  EXPECT_FALSE(rig.spindle.on());
  EXPECT_EQ(rig.spindle.switches(), 2);
  EXPECT_FALSE(rig.app.spindle_on());
}

TEST(AppSpindle, AbortAndAlarmsSwitchItOff) {
  Ready rig;
  rig.host.queue(proto::SpindleCmd{1});
  rig.host.queue(proto::FeedMoveCmd{100000, 0, 5000});
  ASSERT_TRUE(rig.run_until([&] { return rig.spindle.on() && rig.plant.moving(); }, 5000));
  rig.host.send_realtime(proto::AbortCmd{});
  rig.run(20);
  EXPECT_FALSE(rig.spindle.on());
}

TEST(AppDrill, OneFrameDrillsOneHoleAndRetractsToTheStartHeight) {
  Ready rig;
  rig.host.queue(proto::ZMoveCmd{3000, 5000});  // travel height 3 mm
  rig.host.queue(proto::DrillCmd{20000, 10000, 500, -1500, 1000});
  ASSERT_TRUE(rig.run_job(5000));  // the Z move, so the recording starts at the height
  rig.plant.record = true;
  rig.plant.path.clear();
  rig.host.queue(proto::DrillCmd{30000, 10000, 500, -1200, 800});
  ASSERT_TRUE(rig.run_job(20000));
  // The first hole left the tool at its start height; the second one starts there.
  const std::vector<P3> path = rig.recorded_um();
  ASSERT_FALSE(path.empty());
  // Below the start height the tool stands over the hole (within the corner tolerance).
  double min_z = 1e9, worst_off_centre_um = 0;
  for (const P3& p : path) {
    min_z = std::min(min_z, p.z);
    if (p.z < 500 - 2.0) {
      worst_off_centre_um = std::max(worst_off_centre_um, std::hypot(p.x - 30000, p.y - 10000));
    }
  }
  EXPECT_NEAR(min_z, -1200, 2.0);
  EXPECT_LE(worst_off_centre_um, 10.0);
  EXPECT_NEAR(rig.position_um().x, 30000, 1.0);
  EXPECT_NEAR(rig.position_um().y, 10000, 1.0);
  EXPECT_NEAR(rig.position_um().z, 500, 1.0);
  EXPECT_TRUE(rig.host.errors.empty());
}

TEST(AppDrill, ThePlungeRunsAtItsFeed) {
  Ready rig;
  rig.host.queue(proto::ZMoveCmd{2000, 5000});
  ASSERT_TRUE(rig.run_job(5000));
  rig.plant.record = true;
  rig.plant.path.clear();
  rig.host.queue(proto::DrillCmd{0, 0, 1000, -2000, 600});
  ASSERT_TRUE(rig.run_job(20000));
  // Time spent going down between 0.5 mm and -1.5 mm (well inside the plunge): 2 mm at
  // 0.6 mm/s is 3.3 s; the rapid parts of the cycle are far faster.
  const std::vector<P3> path = rig.recorded_um();
  size_t first = 0, last = 0;
  for (size_t i = 1; i < path.size(); ++i) {
    if (path[i].z < path[i - 1].z && path[i].z <= 500 && path[i].z >= -1500) {
      if (first == 0) first = i;
      last = i;
    }
  }
  ASSERT_GT(last, first);
  const double dz_um = path[first].z - path[last].z;
  const double n = double(last - first);
  // The plant records kSubSteps samples a millisecond: time from the sample count.
  const double ms = n / KinematicPlant::kSubSteps;
  const double speed_um_s = dz_um / ms * 1000.0;
  std::printf("[ metrics  ] drill plunge at 600 um/s: measured %.0f um/s\n", speed_um_s);
  EXPECT_NEAR(speed_um_s, 600, 30);
}

TEST(AppDrill, HolesOutsideTheTravelOrBeforeZeroingAreRefused) {
  {
    AppRig rig;
    ASSERT_TRUE(rig.open_session());
    rig.host.queue(proto::DrillCmd{1000, 1000, 500, -500, 500});
    rig.run(50);
    EXPECT_TRUE(has_error(rig.host, ErrorCode::kNotZeroed));
  }
  Ready rig;
  const uint8_t before = rig.app.queue_size();
  rig.host.queue(proto::DrillCmd{1000, 211000, 500, -500, 500});  // Y travel is 210 mm
  rig.run(50);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kOutOfTravel));
  EXPECT_EQ(rig.app.queue_size(), before);
  EXPECT_FALSE(rig.plant.moving());
}

TEST(AppToolOffset, SplineWithAnOffsetRunsBesideItsCurve) {
  Ready rig;
  core::Spline line{};
  line.degree = 1;
  line.control_count = 2;
  line.knot_count = 4;
  line.control[0] = {10000, 10000, core::kWeightOneQ14};
  line.control[1] = {40000, 10000, core::kWeightOneQ14};
  line.knot[2] = line.knot[3] = 1000;
  // +X travel, 500 um to the left: the tool centre runs along y = 10.5 mm.
  for (const auto& f : spline_frames(line, 5000, 500)) rig.host.queue(f);
  ASSERT_TRUE(rig.run_job(20000));
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_NEAR(rig.position_um().x, 40000, 2.0);
  EXPECT_NEAR(rig.position_um().y, 10500, 2.0);
}

TEST(AppStatus, ExecutedFlagTellsARealSeqZeroFromNothingRunYet) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.query_status();
  rig.run(20);
  ASSERT_TRUE(rig.host.have_status);
  EXPECT_EQ(rig.host.status.flags & proto::kStatusExecuted, 0);
  ASSERT_TRUE(rig.zero_here());  // #M ran
  rig.host.query_status();
  rig.run(20);
  EXPECT_NE(rig.host.status.flags & proto::kStatusExecuted, 0);
  EXPECT_EQ(rig.host.status.last_executed_seq, rig.host.first_seq());
}

}  // namespace
}  // namespace fake_app
