// The probe (#Y, #T) through the Application on the kinematic plant with the fake probe
// input: contact latched within one tick and the retract; no contact; refused with the
// probe closed at the start, the spindle on, or no probe input: a coded alarm, nothing moved.
#include <gtest/gtest.h>

#include <cmath>

#include "host_tests/app/app_rig.h"

namespace fake_app {
namespace {

using proto::Alarm;
using proto::MachineState;

struct Ready : AppRig {
  explicit Ready(bool with_probe = true) : AppRig(1, nullptr, with_probe) {
    EXPECT_TRUE(open_session());
    EXPECT_TRUE(zero_here());
  }
  bool probe_result() {
    const int before = host.probe_replies;
    host.query_probe();
    return run_until([&] { return host.probe_replies > before; }, 100);
  }
  bool alarm_raised(Alarm a) {
    return run_until([&] { return !host.alarms.empty() && host.alarms.back().alarm == a; }, 20000);
  }
};

void flat_surface(AppRig* rig, int32_t z_um) {
  rig->probe.set_surface([z_um](int32_t, int32_t) { return z_um; });
}

TEST(AppProbe, ContactHeightIsLatchedWithinOneTickThenZRetractsAboveIt) {
  for (const uint16_t feed : {200, 2000, 5000}) {
    Ready rig;
    flat_surface(&rig, -1234);
    rig.host.queue(proto::FeedMoveCmd{12000, 7000, 10000});
    rig.host.queue(proto::ProbeCmd{-3000, feed, 1000});
    ASSERT_TRUE(rig.run_job(60000)) << feed;
    EXPECT_TRUE(rig.host.alarms.empty());
    ASSERT_TRUE(rig.probe_result());
    EXPECT_EQ(1, rig.host.probe.result);
    EXPECT_EQ(1, rig.host.probe.probe_count);
    EXPECT_NEAR(12000, rig.host.probe.x_um, 1.0);  // read back within 1 um
    EXPECT_NEAR(7000, rig.host.probe.y_um, 1.0);
    // The first closed tick: at most one tick of the feed below the surface (plus 1 um of
    // reading the position back).
    const double per_tick = feed / 1000.0;
    EXPECT_LE(rig.host.probe.z_um, -1234 + 1) << feed;
    EXPECT_GE(rig.host.probe.z_um, -1234 - per_tick - 1) << feed;
    EXPECT_NEAR(rig.position_um().z, rig.host.probe.z_um + 1000, 1.5) << feed;
    EXPECT_NEAR(rig.position_um().x, 12000, 1.0);
  }
}

TEST(AppProbe, NoContactWithinTheLimitIsAlarm8WithZAtTheLimit) {
  Ready rig;
  flat_surface(&rig, -5000);
  rig.host.queue(proto::ProbeCmd{-2000, 2000, 1000});
  rig.host.queue(proto::FeedMoveCmd{9000, 0, 10000});  // dropped by the alarm
  ASSERT_TRUE(rig.alarm_raised(Alarm::kProbeNoContact));
  rig.run(500);
  EXPECT_EQ(rig.app.state(), MachineState::kAlarm);
  EXPECT_NEAR(rig.position_um().z, -2000, 1.5);
  EXPECT_NEAR(rig.position_um().x, 0, 1.0) << "nothing after the probe ran";
  ASSERT_TRUE(rig.probe_result());
  EXPECT_EQ(2, rig.host.probe.result);
  EXPECT_NEAR(rig.host.probe.z_um, -2000, 1.5);
  EXPECT_EQ(rig.display.row[1].substr(0, 14), "PROBE NO TOUCH");
}

TEST(AppProbe, ProbeClosedAtTheStartIsAlarm9AndNothingMoves) {
  Ready rig;
  flat_surface(&rig, -1000);
  rig.probe.force(true);  // the clip touches the tool
  rig.run(10);
  EXPECT_TRUE(rig.app.probe_closed());
  rig.host.queue(proto::ProbeCmd{-3000, 500, 1000});
  ASSERT_TRUE(rig.alarm_raised(Alarm::kProbeClosedAtStart));
  rig.run(200);
  EXPECT_NEAR(rig.position_um().z, 0, 0.5);
  ASSERT_TRUE(rig.probe_result());
  EXPECT_EQ(0, rig.host.probe.result) << "no probe ran";
}

TEST(AppProbe, SpindleOnIsAlarm10AndNothingMoves) {
  Ready rig;
  flat_surface(&rig, -1000);
  rig.host.queue(proto::SpindleCmd{1});
  rig.host.queue(proto::ProbeCmd{-3000, 500, 1000});
  ASSERT_TRUE(rig.alarm_raised(Alarm::kProbeSpindleOn));
  rig.run(200);
  EXPECT_NEAR(rig.position_um().z, 0, 0.5);
  EXPECT_FALSE(rig.spindle.on()) << "the alarm stops the spindle too";
}

TEST(AppProbe, AMachineWithoutAProbeInputRefusesWithAlarm11) {
  Ready rig(false);
  rig.host.queue(proto::ProbeCmd{-3000, 500, 1000});
  ASSERT_TRUE(rig.alarm_raised(Alarm::kProbeMissing));
  rig.run(200);
  EXPECT_NEAR(rig.position_um().z, 0, 0.5);
}

// One closed tick (a bounce, a spark of noise) is not a contact: the descent goes on to the
// real surface.
TEST(AppProbe, AOneTickGlitchIsDebouncedAway) {
  Ready rig;
  flat_surface(&rig, -1500);
  rig.host.queue(proto::ProbeCmd{-3000, 1000, 500});
  ASSERT_TRUE(rig.run_until([&] { return rig.position_um().z < -600; }, 20000));
  rig.probe.force(true);
  rig.step();
  rig.probe.release();
  ASSERT_TRUE(rig.run_job(20000));
  ASSERT_TRUE(rig.probe_result());
  EXPECT_EQ(1, rig.host.probe.result);
  EXPECT_NEAR(rig.host.probe.z_um, -1500, 2.5);
  EXPECT_NEAR(rig.position_um().z, rig.host.probe.z_um + 500, 1.5);
}

// A grid of probes in one stream, as `engraver probe` sends it: each result is the surface
// under its point (a tilted board), the counts go up one by one.
TEST(AppProbe, ProbesInOneStreamEachFindTheSurfaceUnderThem) {
  Ready rig;
  rig.probe.set_surface([](int32_t x, int32_t y) { return -300 - x / 100 + y / 200; });
  struct Result {
    int32_t x, y, z;
  };
  std::vector<Result> got;
  for (int i = 0; i < 4; ++i) {
    const int32_t x = 10000 * (i % 2), y = 10000 * (i / 2);
    rig.host.queue(proto::ZMoveCmd{1000, 5000});
    rig.host.queue(proto::RapidMoveCmd{x, y});
    rig.host.queue(proto::ProbeCmd{-2000, 1000, 500});
    ASSERT_TRUE(rig.run_job(30000));
    ASSERT_TRUE(rig.probe_result());
    EXPECT_EQ(i + 1, rig.host.probe.probe_count);
    got.push_back({rig.host.probe.x_um, rig.host.probe.y_um, rig.host.probe.z_um});
  }
  for (const Result& r : got) EXPECT_NEAR(r.z, -300 - r.x / 100 + r.y / 200, 2.0);
  EXPECT_TRUE(rig.host.alarms.empty());
}

}  // namespace
}  // namespace fake_app
