// Whole jobs through the Application: frames in (byte by byte, in chunks, mangled), motion
// out on the kinematic plant; zeroing, hold, abort, limit switch, flow control, LCD.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

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

// Queues a representative job; returns the commanded path (from the origin) for error checks.
std::vector<P3> queue_standard_job(AppRig& rig, const core::Spline& s) {
  rig.host.queue(proto::ResolutionCmd{2000, 2});
  rig.host.queue(proto::RapidMoveCmd{s.control[0].x_um, s.control[0].y_um});
  rig.host.queue(proto::ZMoveCmd{-200, 500});
  for (const auto& f : spline_frames(s, 10000)) rig.host.queue(f);
  rig.host.queue(proto::ZMoveCmd{1000, 2000});
  rig.host.queue(proto::FeedMoveCmd{120000, 60000, 10000});
  std::vector<P3> path{{0, 0, 0},
                       {double(s.control[0].x_um), double(s.control[0].y_um), 0},
                       {double(s.control[0].x_um), double(s.control[0].y_um), -200}};
  for (const P3& p : dense_points(s, 200, -200)) path.push_back(p);
  path.push_back({path.back().x, path.back().y, 1000});
  path.push_back({120000, 60000, 1000});
  return path;
}

TEST(AppSession, StatusWorksBeforeASessionButQueuedFramesAreRefused) {
  AppRig rig;
  rig.host.query_status();
  rig.run(5);
  EXPECT_TRUE(rig.host.have_status);
  EXPECT_EQ(rig.host.status.state, MachineState::kIdle);
  rig.host.send_raw(proto::kCmdZeroing, 1, {7});
  rig.run(5);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kNoSession));
  EXPECT_EQ(rig.app.state(), MachineState::kIdle);
}

// docs/protocol.md section 4: before the first #I, #R #V #C get kNoSession.
TEST(AppSession, ResumeOverrideAndClearBeforeASessionGetNoSession) {
  AppRig rig;
  rig.host.send_raw(proto::kCmdResume, 1, {});
  rig.host.send_raw(proto::kCmdOverride, 2, {50});
  rig.host.send_raw(proto::kCmdClearAlarm, 3, {});
  rig.run(5);
  ASSERT_EQ(rig.host.errors.size(), 3u);
  for (const auto& e : rig.host.errors) EXPECT_EQ(e.code, ErrorCode::kNoSession);
  EXPECT_EQ(rig.host.acks, 0);
}

// ... while #H and #X always act: stopping is always allowed.
TEST(AppSession, HoldBeforeASessionIsAcknowledgedAndHolds) {
  AppRig rig;
  rig.host.send_raw(proto::kCmdHold, 1, {});
  rig.run(5);
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_EQ(rig.host.acks, 1);
  EXPECT_EQ(rig.app.state(), MachineState::kHeld);
}

TEST(AppSession, AbortBeforeASessionIsAcknowledgedAndFlagsTheStreamUntilSessionStart) {
  AppRig rig;
  rig.host.send_raw(proto::kCmdAbort, 1, {});
  rig.run(5);
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_EQ(rig.host.acks, 1);
  EXPECT_TRUE(rig.app.dispatcher().aborted());
  ASSERT_TRUE(rig.open_session());
  EXPECT_FALSE(rig.app.dispatcher().aborted());
  ASSERT_TRUE(rig.zero_here());  // the fresh stream runs queued work
}

// #I stops and clears everything, a hold included: the new session starts idle.
TEST(AppSession, SessionStartAfterAnEarlyHoldStartsIdleAndRunsQueuedWork) {
  AppRig rig;
  rig.host.send_raw(proto::kCmdHold, 200, {});
  rig.run(5);
  ASSERT_EQ(rig.app.state(), MachineState::kHeld);
  ASSERT_TRUE(rig.open_session());
  rig.run(5);
  EXPECT_EQ(rig.app.state(), MachineState::kIdle);
  ASSERT_TRUE(rig.zero_here());
  EXPECT_TRUE(rig.host.errors.empty());
}

// docs/protocol.md section 4: the controller speaks versions 2 and 3 and answers in the one
// asked for; another is refused naming the newest it speaks.
TEST(AppSession, VersionsTwoAndThreeOpenASessionInThatVersionOthersAreRefused) {
  for (uint8_t version : {2, 3}) {
    AppRig rig;
    rig.host.open_session(version);
    rig.run(5);
    EXPECT_TRUE(rig.host.session_open) << int(version);
    EXPECT_EQ(rig.host.session.protocol_version, version);
    EXPECT_TRUE(rig.host.errors.empty());
  }
  for (uint8_t version : {1, 4}) {
    AppRig rig;
    rig.host.open_session(version);
    rig.run(5);
    EXPECT_FALSE(rig.host.session_open) << int(version);
    ASSERT_EQ(rig.host.errors.size(), 1u);
    EXPECT_EQ(rig.host.errors[0].code, ErrorCode::kVersionUnsupported);
    EXPECT_EQ(rig.host.errors[0].detail, proto::kProtocolVersion);
  }
}

// *? reports the position of each axis in its own field (docs/protocol.md, *?).
TEST(AppSession, StatusReplyCarriesEachAxisPosition) {
  AppRig rig;
  rig.host.open_session();
  ASSERT_TRUE(rig.run_until([&] { return rig.host.session_open; }, 100));
  ASSERT_TRUE(rig.zero_here());
  rig.host.queue(proto::ZMoveCmd{2500, 5000});
  rig.host.queue(proto::FeedMoveCmd{12000, 7000, 5000});
  ASSERT_TRUE(rig.run_job(20000));
  rig.host.have_status = false;
  rig.host.query_status();
  ASSERT_TRUE(rig.run_until([&] { return rig.host.have_status; }, 100));
  EXPECT_NEAR(rig.host.status.x_um, 12000, 1);
  EXPECT_NEAR(rig.host.status.y_um, 7000, 1);
  EXPECT_NEAR(rig.host.status.z_um, 2500, 1);
}

// *I reports the travel the controller checks against, each axis in its field, and the
// fastest feeds (docs/protocol.md section 4).
TEST(AppSession, SessionReplyCarriesEachAxisTravelAndTheFastestFeeds) {
  AppRig rig;
  rig.host.open_session();
  ASSERT_TRUE(rig.run_until([&] { return rig.host.session_open; }, 100));
  const proto::SessionReply& r = rig.host.session;
  EXPECT_EQ(r.travel_x_um, rig.cfg.axis[config::kAxisX].travel_um);
  EXPECT_EQ(r.travel_y_um, rig.cfg.axis[config::kAxisY].travel_um);
  EXPECT_EQ(r.travel_z_um, rig.cfg.axis[config::kAxisZ].travel_um);
  EXPECT_NE(r.travel_x_um, r.travel_y_um);  // the default machine tells the axes apart
  EXPECT_NE(r.travel_y_um, r.travel_z_um);
  EXPECT_EQ(r.max_feed_xy_um_per_s, std::min(rig.cfg.axis[config::kAxisX].max_speed_um_per_s,
                                             rig.cfg.axis[config::kAxisY].max_speed_um_per_s));
  EXPECT_EQ(r.max_feed_z_um_per_s, rig.cfg.axis[config::kAxisZ].max_speed_um_per_s);
  EXPECT_EQ(r.queue_slots, app::CommandQueue::kCapacity);
}

// docs/protocol.md section 4: version 3 only adds #Q. In a version-2 session a #Q is an
// unknown command (detail: the version that brings it), nothing is stored; the same frames
// run in a version-3 session. (Frames of the document's examples, section 6.)
TEST(AppSession, ContourFramesAreAnUnknownCommandInAVersionTwoSession) {
  const std::vector<uint8_t> header = {2, 1, 5, 0, 8, 0, 0xD0, 7, 0, 0, 0, 0};
  const std::vector<uint8_t> contour = {0x00, 0x05, 0xA0, 0x9C, 0x01, 0x90, 0x4E, 0xC0, 0xB8,
                                        0x02, 0x00, 0xA1, 0x9C, 0x01, 0x90, 0x4E, 0x9F, 0x37};
  for (uint8_t version : {2, 3}) {
    AppRig rig;
    rig.host.open_session(version);
    ASSERT_TRUE(rig.run_until([&] { return rig.host.session_open; }, 100));
    ASSERT_TRUE(rig.zero_here());
    rig.host.queue(TestHost::Frame{proto::kCmdSplineHeader, header});
    rig.host.queue(TestHost::Frame{proto::kCmdSplineContour, contour});
    if (version == 2) {
      rig.run(200);
      ASSERT_EQ(rig.host.errors.size(), 1u);
      EXPECT_EQ(rig.host.errors[0].code, ErrorCode::kUnknownCommand);
      EXPECT_EQ(rig.host.errors[0].detail, proto::kContourFramesVersion);
      EXPECT_EQ(rig.host.acked(), 2u);  // #M and #B; the #Q not stored
      continue;
    }
    ASSERT_TRUE(rig.run_job(20000));
    EXPECT_TRUE(rig.host.errors.empty());
    EXPECT_NEAR(rig.position_um().x, 25000, 1.0);  // the quarter circle's end
    EXPECT_NEAR(rig.position_um().y, 10000, 1.0);
  }
}

TEST(AppZeroing, JoystickJogsWithARampedSpeedAndConfirmSetsTheZero) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::ZeroingCmd{7});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kZeroing; }, 2000));
  rig.inputs.bits = hal::kJoyRight;
  rig.run(500);
  const double after_half_s = rig.position_um().x;
  rig.run(500);
  const double after_one_s = rig.position_um().x;
  EXPECT_GT(after_half_s, 50.0);                        // moving right
  EXPECT_GT(after_one_s - after_half_s, after_half_s);  // and faster the longer it is held
  rig.inputs.bits = hal::kButtonZ;                      // Z toggle: up/down now drive Z
  rig.run(5);
  rig.inputs.bits = hal::kJoyDown;
  rig.run(300);
  EXPECT_LT(rig.position_um().z, -20.0);
  rig.inputs.bits = hal::kButtonConfirm;
  rig.run(30);
  rig.inputs.bits = 0;
  ASSERT_TRUE(rig.run_until([&] { return rig.app.zeroed(); }, 2000));
  rig.run(300);
  EXPECT_EQ(rig.app.state(), MachineState::kIdle);
  EXPECT_NEAR(rig.position_um().x, 0, 1.0);  // the chip's x_actual was set to zero
  EXPECT_NEAR(rig.position_um().z, 0, 1.0);
  EXPECT_TRUE(rig.host.status.flags & proto::kStatusZeroed);
}

// The Z button is a toggle: each press (the panel reports it while pressed) switches the
// joystick's down/up between Y and Z (docs/firmware.md, Zeroing).
TEST(AppZeroing, EachZButtonPressSwitchesDownUpBetweenYAndZ) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::ZeroingCmd{7});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kZeroing; }, 2000));
  rig.run(50);  // the tick has started the jog (buttons down at its start are ignored)
  rig.inputs.bits = hal::kButtonZ;  // first press: Z mode on
  rig.run(20);
  rig.inputs.bits = hal::kJoyDown;  // released; down now drives Z
  rig.run(300);
  rig.inputs.bits = 0;
  rig.run(300);
  const P3 after_z = rig.position_um();
  EXPECT_LT(after_z.z, -20.0);
  EXPECT_NEAR(after_z.y, 0, 1.0);
  rig.inputs.bits = hal::kButtonZ;  // second press: back to Y
  rig.run(20);
  rig.inputs.bits = hal::kJoyDown;
  rig.run(300);
  rig.inputs.bits = 0;
  rig.run(300);
  EXPECT_LT(rig.position_um().y, -20.0);
  EXPECT_NEAR(rig.position_um().z, after_z.z, 1.0);
}

TEST(AppZeroing, HoldingTheZButtonSwitchesOnlyOnce) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::ZeroingCmd{7});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kZeroing; }, 2000));
  rig.run(50);  // the tick has started the jog (buttons down at its start are ignored)
  rig.inputs.bits = hal::kButtonZ;
  rig.run(1000);  // held for a second: still one press
  rig.inputs.bits = hal::kJoyDown;
  rig.run(300);
  rig.inputs.bits = 0;
  rig.run(300);
  EXPECT_LT(rig.position_um().z, -20.0);
  EXPECT_NEAR(rig.position_um().y, 0, 1.0);
}

TEST(AppZeroing, ClearButtonCancelsWithoutChangingTheZero) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::ZeroingCmd{7});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kZeroing; }, 2000));
  rig.inputs.bits = hal::kJoyUp;
  rig.run(300);
  rig.inputs.bits = hal::kButtonClear;
  rig.run(30);
  rig.inputs.bits = 0;
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kIdle; }, 2000));
  EXPECT_FALSE(rig.app.zeroed());
  EXPECT_EQ(rig.plant.position_writes, 0);
  EXPECT_GT(rig.position_um().y, 20.0);
}

TEST(AppJob, MotionBeforeZeroingIsRefusedWithNotZeroed) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::FeedMoveCmd{10000, 0, 5000});
  rig.run(50);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kNotZeroed));
  EXPECT_EQ(rig.app.queue_size(), 0);
  EXPECT_FALSE(rig.plant.moving());
}

TEST(AppJob, WholeJobFedByteByByteFollowsThePathWithinTenMicrometres) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.impair.max_chunk = 1;  // one byte per millisecond
  const core::Spline s = blob_spline(60000, 60000, 20000, 12);
  const std::vector<P3> path = queue_standard_job(rig, s);
  rig.plant.record = true;
  ASSERT_TRUE(rig.run_job(200000));
  EXPECT_NEAR(rig.position_um().x, 120000, 1.0);
  EXPECT_NEAR(rig.position_um().y, 60000, 1.0);
  EXPECT_NEAR(rig.position_um().z, 1000, 1.0);
  const double err = max_contour_error(rig.recorded_um(), path);
  std::printf("[ metrics  ] byte-by-byte job: contour error %.2f um (incl. 2 um chord tolerance)\n",
              err);
  EXPECT_LE(err, 10.0);
  EXPECT_TRUE(rig.host.errors.empty());
}

TEST(AppJob, MangledLinkStillRunsEveryCommandExactlyOnce) {
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    AppRig rig(seed);
    ASSERT_TRUE(rig.open_session());
    ASSERT_TRUE(rig.zero_here());
    rig.host.impair = {0.1, 0.1, 0.15, 0.3, 40};
    const core::Spline s = blob_spline(60000, 60000, 15000, 40);
    queue_standard_job(rig, s);
    const uint16_t items_before = rig.app.items_done();
    ASSERT_TRUE(rig.run_job(300000)) << "seed " << seed;
    // #U, #F, #Z, spline, #Z, #G: six items, each run once whatever was resent.
    EXPECT_EQ(rig.app.items_done() - items_before, 6) << "seed " << seed;
    EXPECT_EQ(rig.app.items_stored() - items_before, 6) << "seed " << seed;
    EXPECT_NEAR(rig.position_um().x, 120000, 1.0);
    EXPECT_GT(rig.app.dispatcher().rejected_frames(), 0);  // the mangling did reach it
  }
}

TEST(AppJob, DuplicateFrameIsAcknowledgedAgainButRunOnce) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.impair.duplicate = 1.0;  // every queued frame arrives twice
  rig.host.queue(proto::FeedMoveCmd{5000, 0, 10000});
  rig.host.queue(proto::FeedMoveCmd{5000, 5000, 10000});
  ASSERT_TRUE(rig.run_job(20000));
  EXPECT_EQ(rig.app.items_stored(), 3);  // #M and the two moves
  EXPECT_GE(rig.host.acks, 5);
  EXPECT_NEAR(rig.position_um().y, 5000, 1.0);
}

TEST(AppJob, OutOfTravelTargetIsRefusedAndNothingIsStored) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  const uint8_t before = rig.app.queue_size();
  rig.host.queue(proto::FeedMoveCmd{297001, 0, 10000});  // X travel is 297 mm
  rig.run(50);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kOutOfTravel));
  EXPECT_EQ(rig.app.queue_size(), before);
  EXPECT_FALSE(rig.plant.moving());
}

TEST(AppJob, SplineControlPointOutsideTheTravelIsRefused) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  core::Spline s = blob_spline(60000, 60000, 10000, 6);
  s.control[3].y_um = 210001;  // Y travel is 210 mm
  for (const auto& f : spline_frames(s, 10000)) rig.host.queue(f);
  rig.run(200);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kOutOfTravel));
}

TEST(AppJob, SplineHeaderClaimingMoreThanFitsIsRefused) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  // 65 control points: one more than a slot holds. Built by hand: the encoder refuses it.
  const uint8_t payload[12] = {3, 0, 65, 0, 69, 0, 0x10, 0x27, 0, 0, 0, 0};
  rig.host.queue(TestHost::Frame{proto::kCmdSplineHeader, {payload, payload + 12}});
  rig.run(50);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kFieldRange));
}

TEST(AppJob, SplineDataOutOfOrderIsRefusedWithSplineSequence) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  const core::Spline s = blob_spline(60000, 60000, 10000, 12);
  const auto frames = spline_frames(s, 10000);
  rig.host.queue(frames[0]);  // #B
  rig.host.queue(frames[2]);  // second #D before the first
  rig.run(100);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kSplineSequence));
}

TEST(AppJob, InvalidSplineIsRefusedWithItsGeometryCode) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  core::Spline s = blob_spline(60000, 60000, 10000, 6);
  s.knot[5] = -5;  // decreasing knots
  for (const auto& f : spline_frames(s, 10000)) rig.host.queue(f);
  rig.run(300);
  ASSERT_TRUE(has_error(rig.host, ErrorCode::kGeometry));
  for (const auto& e : rig.host.errors) {
    if (e.code == ErrorCode::kGeometry)
      EXPECT_EQ(e.detail, uint8_t(core::GeometryError::kKnotsDecreasing));
  }
}

TEST(AppFlowControl, FullQueueDelaysTheAckAndLosesNothing) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  // 40 short moves: more than the 16 queue slots, so acks must wait for motion.
  for (int i = 1; i <= 40; ++i) {
    rig.host.queue(proto::FeedMoveCmd{i * 1000, (i % 2) * 1000, 10000});
  }
  bool saw_held = false;
  ASSERT_TRUE(rig.run_until(
      [&] {
        saw_held = saw_held || rig.app.dispatcher().frame_held();
        return rig.host.all_acked() && rig.app.state() == MachineState::kIdle &&
               !rig.plant.moving();
      },
      60000));
  EXPECT_TRUE(saw_held);
  EXPECT_EQ(rig.app.items_done(), 41);  // #M + 40 moves, each once
  EXPECT_NEAR(rig.position_um().x, 40000, 1.0);
  EXPECT_NEAR(rig.position_um().y, 0, 1.0);
}

TEST(AppMotion, HoldStopsMidJobAndResumeFinishesIt) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.queue(proto::FeedMoveCmd{50000, 0, 10000});
  rig.run(1000);
  rig.host.send_realtime(proto::HoldCmd{});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kHeld; }, 500));
  rig.run(50);
  const double held_x = rig.position_um().x;
  EXPECT_GT(held_x, 5000);
  EXPECT_LT(held_x, 50000);
  rig.run(3000);  // held well past the link watchdog: still nothing moves
  EXPECT_NEAR(rig.position_um().x, held_x, 0.01);
  rig.host.send_realtime(proto::ResumeCmd{});
  ASSERT_TRUE(rig.run_job(20000));
  EXPECT_NEAR(rig.position_um().x, 50000, 1.0);
}

TEST(AppMotion, AbortStopsRefusesTheRestAndANewSessionWorks) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.queue(proto::FeedMoveCmd{50000, 0, 10000});
  rig.host.queue(proto::FeedMoveCmd{50000, 50000, 10000});
  rig.run(1000);
  rig.host.send_realtime(proto::AbortCmd{});
  ASSERT_TRUE(rig.run_until(
      [&] { return !rig.plant.moving() && rig.app.state() == MachineState::kIdle; }, 2000));
  const P3 stopped = rig.position_um();
  EXPECT_LT(stopped.x, 50000);
  EXPECT_NEAR(stopped.y, 0, 1.0);
  EXPECT_EQ(rig.app.queue_size(), 0);
  rig.host.queue(proto::FeedMoveCmd{0, 0, 10000});
  rig.run(100);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kAborted));
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::FeedMoveCmd{0, 0, 10000});
  ASSERT_TRUE(rig.run_job(20000));
  EXPECT_NEAR(rig.position_um().x, 0, 1.0);
}

TEST(AppMotion, SessionResetMidJobStopsAlongThePathAndStartsAFreshStream) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.queue(proto::FeedMoveCmd{50000, 0, 10000});
  rig.run(1000);
  ASSERT_TRUE(rig.open_session());  // #I while moving
  ASSERT_TRUE(rig.run_until([&] { return !rig.plant.moving(); }, 2000));
  EXPECT_LT(rig.position_um().x, 50000 - 1000);
  EXPECT_NEAR(rig.position_um().y, 0, 1.0);
  EXPECT_TRUE(rig.app.zeroed());  // a session reset keeps the zero
  rig.host.queue(proto::FeedMoveCmd{0, 2000, 10000});
  ASSERT_TRUE(rig.run_job(20000));
  EXPECT_NEAR(rig.position_um().x, 0, 1.0);
  EXPECT_NEAR(rig.position_um().y, 2000, 1.0);
}

TEST(AppZeroing, AbortWhileZeroingCancelsIt) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.queue(proto::ZeroingCmd{7});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kZeroing; }, 2000));
  rig.inputs.bits = hal::kJoyRight;
  rig.run(200);
  rig.host.send_realtime(proto::AbortCmd{});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kIdle; }, 2000));
  rig.run(200);  // the joystick is still pushed: nothing moves outside zeroing
  EXPECT_FALSE(rig.plant.moving());
  EXPECT_FALSE(rig.app.zeroed());
  EXPECT_EQ(rig.plant.position_writes, 0);
}

TEST(AppMotion, LimitSwitchStopsWithinOneTickAndNothingMovesUntilCleared) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.plant.axis[0].limit_right_usteps = 30000 * 2.56;  // switch at X = 30 mm
  rig.host.queue(proto::FeedMoveCmd{80000, 0, 10000});
  ASSERT_TRUE(rig.run_until([&] { return rig.plant.limits() != 0; }, 10000));
  // The tick after the switch closed wrote zero velocities on every axis.
  rig.app.tick_1ms();
  EXPECT_EQ(rig.plant.v_target[0], 0);
  EXPECT_EQ(rig.plant.v_target[1], 0);
  EXPECT_EQ(rig.plant.v_target[2], 0);
  rig.run(200);
  EXPECT_EQ(rig.app.state(), MachineState::kAlarm);
  EXPECT_FALSE(rig.plant.moving());
  ASSERT_FALSE(rig.host.alarms.empty());
  EXPECT_EQ(rig.host.alarms[0].alarm, proto::Alarm::kLimitSwitch);
  const P3 stopped = rig.position_um();
  rig.host.queue(proto::FeedMoveCmd{0, 0, 10000});
  rig.run(1000);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kAlarmActive));
  EXPECT_NEAR(rig.position_um().x, stopped.x, 0.01);
  rig.host.send_realtime(proto::ClearAlarmCmd{});
  rig.run(100);
  EXPECT_EQ(rig.app.state(), MachineState::kIdle);
  EXPECT_FALSE(rig.app.zeroed());  // position suspect: zero again
  EXPECT_NEAR(rig.position_um().x, stopped.x, 0.01);
}

TEST(AppMotion, LostLinkGivesAControlledStopAtTheEndOfWhatWasReceived) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  const core::Spline s = blob_spline(40000, 40000, 20000, 16);
  const auto frames = spline_frames(s, 10000);
  rig.host.queue(proto::FeedMoveCmd{s.control[0].x_um, s.control[0].y_um, 10000});
  // The #B and only some #D frames arrive, then the link goes silent.
  for (size_t i = 0; i + 1 < frames.size(); ++i) rig.host.queue(frames[i]);
  rig.plant.record = true;
  ASSERT_TRUE(rig.run_until([&] { return rig.host.all_acked(); }, 20000));
  rig.host.impair.drop = 1.0;
  ASSERT_TRUE(rig.run_until([&] { return !rig.plant.moving(); }, 30000));
  rig.run(3000);
  EXPECT_FALSE(rig.plant.moving());
  // It waits at the spline start for the rest of the data: no jump, no run-away.
  EXPECT_NEAR(rig.position_um().x, s.control[0].x_um, 1.0);
  EXPECT_NEAR(rig.position_um().y, s.control[0].y_um, 1.0);
}

TEST(AppMotion, EmptyCoordinateBufferMidCurveStopsOnThePath) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  const core::Spline s = blob_spline(40000, 40000, 20000, 16);
  rig.host.queue(proto::FeedMoveCmd{s.control[0].x_um, s.control[0].y_um, 10000});
  for (const auto& f : spline_frames(s, 10000)) rig.host.queue(f);
  std::vector<P3> path{{0, 0, 0}};
  for (const P3& p : dense_points(s, 200, 0)) path.push_back(p);
  rig.plant.record = true;
  const uint16_t done_before = rig.app.items_done();
  ASSERT_TRUE(rig.run_until([&] { return rig.app.items_done() > done_before; }, 30000));
  rig.run(1000);  // well into the curve
  ASSERT_TRUE(rig.plant.moving());
  // Stop running the background loop for 6 s (the host goes on polling): the tick uses up
  // the ring and stops.
  for (int i = 0; i < 6000; ++i) {
    rig.app.tick_1ms();
    rig.plant.step_1ms();
    rig.host.step(++rig.now);
  }
  EXPECT_FALSE(rig.plant.moving());
  ASSERT_TRUE(rig.run_job(60000));
  EXPECT_LE(max_contour_error(rig.recorded_um(), path), 10.0);
}

TEST(AppMotion, SilentLinkWhileRunningHoldsTheMachineAfterTwoSeconds) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.queue(proto::FeedMoveCmd{100000, 0, 10000});
  rig.run(500);
  // The host falls silent (no #? either): only the controller runs on.
  for (int i = 0; i < 2600; ++i) {
    rig.app.tick_1ms();
    rig.plant.step_1ms();
    rig.app.poll();
  }
  EXPECT_EQ(rig.app.state(), MachineState::kHeld);
  EXPECT_LT(rig.position_um().x, 100000 - 1000);
  rig.host.query_status();
  rig.run(5);
  EXPECT_TRUE(rig.host.status.flags & proto::kStatusLinkHold);
  rig.host.send_realtime(proto::ResumeCmd{});
  ASSERT_TRUE(rig.run_job(20000));
  EXPECT_NEAR(rig.position_um().x, 100000, 1.0);
}

std::vector<uint8_t> payload_of(const TestHost::Frame& f) {
  return f.payload;
}

TEST(AppSequence, StaleRealTimeFrameIsRefusedAndANewerOneActs) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.send_raw(proto::kCmdHold, 50, {});
  rig.run(5);
  EXPECT_EQ(rig.app.state(), MachineState::kHeld);
  rig.host.send_raw(proto::kCmdResume, 40, {});  // older than the hold: superseded
  rig.run(5);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kSeqStale));
  EXPECT_EQ(rig.app.state(), MachineState::kHeld);
  rig.host.send_raw(proto::kCmdResume, 51, {});
  rig.run(5);
  EXPECT_EQ(rig.app.state(), MachineState::kIdle);
}

// A retransmitted stop whose first copy was lost arrives after a newer real-time frame.
TEST(AppSequence, OlderHoldStillActsButDoesNotMoveTheSeqBack) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.send_raw(proto::kCmdOverride, 50, {80});
  rig.run(5);
  rig.host.send_raw(proto::kCmdHold, 40, {});  // older than the override
  rig.run(5);
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_EQ(rig.app.state(), MachineState::kHeld);
  rig.host.send_raw(proto::kCmdResume, 45, {});  // still older than 50: refused
  rig.run(5);
  EXPECT_TRUE(has_error(rig.host, ErrorCode::kSeqStale));
  EXPECT_EQ(rig.app.state(), MachineState::kHeld);
}

TEST(AppSequence, OlderAbortStillActs) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  rig.host.send_raw(proto::kCmdOverride, 50, {80});
  rig.host.send_raw(proto::kCmdAbort, 49, {});
  rig.run(5);
  EXPECT_TRUE(rig.host.errors.empty());
  EXPECT_TRUE(rig.app.dispatcher().aborted());
}

TEST(AppSequence, FrameAheadOfTheExpectedSeqIsAGap) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  const uint8_t next = uint8_t(rig.host.first_seq() + rig.host.acked());
  rig.host.send_raw(proto::kCmdFeedMove, uint8_t(next + 2),
                    payload_of(TestHost::make(proto::FeedMoveCmd{1000, 0, 1000})));
  rig.run(5);
  ASSERT_FALSE(rig.host.errors.empty());
  EXPECT_EQ(rig.host.errors.back().code, ErrorCode::kSeqGap);
  EXPECT_EQ(rig.host.errors.back().next_expected_seq, next);
  EXPECT_EQ(rig.app.queue_size(), 0);
}

TEST(AppSequence, SecondNewFrameWhileOneIsHeldGetsBusy) {
  AppRig rig;
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  uint8_t seq = uint8_t(rig.host.first_seq() + rig.host.acked());
  // 16 slots fill, the 17th frame is held, the 18th is refused with kBusy.
  for (int i = 1; i <= 18; ++i) {
    rig.host.send_raw(proto::kCmdFeedMove, seq++,
                      payload_of(TestHost::make(proto::FeedMoveCmd{i * 100, 0, 1000})));
  }
  rig.run(3);
  EXPECT_TRUE(rig.app.dispatcher().frame_held());
  ASSERT_FALSE(rig.host.errors.empty());
  EXPECT_EQ(rig.host.errors.back().code, ErrorCode::kBusy);
  EXPECT_EQ(rig.app.queue_size(), 16);
}

TEST(AppRobustness, RandomCrcValidFramesNeverTrapAndNeverLeaveTheTravel) {
  AppRig rig(7);
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  std::mt19937 rng(11);
  const uint8_t letters[] = {'S', 'B', 'D', 'U', 'G', 'F', 'Z', 'M', 'H',
                             'R', 'V', 'C', 'X', 'I', '?', 'Q', 'K'};
  uint8_t seq = uint8_t(rig.host.first_seq() + rig.host.acked());
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> payload(rng() % 20);
    for (auto& b : payload) b = uint8_t(rng());
    const uint8_t letter = letters[rng() % sizeof letters];
    if (letter == 'I') payload.assign(1, rng() % 4 ? 1 : 2);
    rig.host.send_raw(letter, rng() % 4 ? seq++ : uint8_t(rng()), payload);
    rig.run(1 + rng() % 5);
    for (int a = 0; a < 3; ++a) {
      const double t = config::default_machine_config().axis[a].travel_um + 1.0;
      const double p = a == 0   ? rig.position_um().x
                       : a == 1 ? rig.position_um().y
                                : rig.position_um().z;
      ASSERT_LE(std::abs(p), t) << "frame " << i;
    }
  }
  rig.host.send_realtime(proto::AbortCmd{});
  rig.run(3000);
  EXPECT_FALSE(rig.plant.moving());
}

TEST(AppScreen, ShowsStateJobProgressTextAndErrors) {
  AppRig rig;
  rig.run(200);
  EXPECT_EQ(rig.display.row[0], "IDLE");
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.run(200);
  EXPECT_EQ(rig.display.row[0].substr(0, 5), "READY");
  EXPECT_EQ(rig.display.row[1], "X0.00 Y0.00");
  proto::TextCmd t{};
  t.row = 1;
  t.length = 5;
  memcpy(t.text, "HELLO", 5);
  rig.host.queue(t);
  rig.run(300);
  EXPECT_EQ(rig.display.row[1], "HELLO");
  rig.host.queue(proto::FeedMoveCmd{900000, 0, 10000});
  rig.run(300);
  EXPECT_EQ(rig.display.row[1], "ERR 37 #4");  // out of travel, next expected seq 4
}

TEST(AppMemory, ApplicationStateFitsTheTargetBudget) {
  // Host sizes (8-byte pointers); the AVR proxy gives 4912 bytes, see docs/performance.md.
  std::printf(
      "[ sizes    ] Application %zu, CoordinateRing %zu (PlanEntry %zu), SplineStore %zu, "
      "CommandQueue %zu, Dispatcher %zu\n",
      sizeof(app::Application), sizeof(app::CoordinateRing), sizeof(app::PlanEntry),
      sizeof(app::SplineStore), sizeof(app::CommandQueue), sizeof(app::Dispatcher));
  // 5632 before issue 25; +568 for the height map (16 x 16 heights of 12 bits, 384 bytes,
  // with its grid) and the probe's state.
  EXPECT_LE(sizeof(app::Application), 6200u);  // leaves ~2 KB of the 8 KB for port + stack
}

}  // namespace
}  // namespace fake_app
