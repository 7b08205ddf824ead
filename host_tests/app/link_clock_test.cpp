// The board's link clock (hal::LinkClock): when a board gives one, the link's time-outs (the
// 200 ms inter-byte frame time-out, the 2 s link watchdog) count it, not the 1 ms tick. The
// simulator serving another program relies on it: its ticks run faster than the wall clock.
#include <gtest/gtest.h>

#include "host_tests/app/app_rig.h"

namespace fake_app {
namespace {

using proto::MachineState;

// A link clock the test sets by hand.
class ManualLinkClock : public hal::LinkClock {
 public:
  uint16_t link_ms() override { return ms; }
  uint16_t ms = 0;
};

std::vector<uint8_t> status_query_frame(uint8_t seq) {
  uint8_t buf[proto::kMaxFrameBytes];
  const uint8_t n = proto::encode_frame(proto::kCommandStart, proto::kCmdStatus, seq, nullptr, 0,
                                        buf, sizeof buf);
  return std::vector<uint8_t>(buf, buf + n);
}

// ticks milliseconds of the controller (tick, plant, background pass, host) in which the link
// clock advances by link_ms in all.
void run_with_link_time(AppRig& rig, ManualLinkClock& clock, int ticks, int link_ms) {
  for (int i = 0; i < ticks; ++i) {
    clock.ms =
        static_cast<uint16_t>(clock.ms + (link_ms * (i + 1)) / ticks - (link_ms * i) / ticks);
    rig.step();
  }
}

TEST(AppLinkClock, APartialFrameIsDroppedAfter200MsOfTheLinkClockNotOfTheTick) {
  ManualLinkClock clock;
  AppRig rig(1, &clock);
  const std::vector<uint8_t> f = status_query_frame(7);
  // 1 s of ticks but 150 ms of link time between the two halves: the frame is answered.
  rig.link.rx.insert(rig.link.rx.end(), f.begin(), f.begin() + 3);
  run_with_link_time(rig, clock, 1000, 150);
  rig.link.rx.insert(rig.link.rx.end(), f.begin() + 3, f.end());
  rig.run(5);
  EXPECT_TRUE(rig.host.have_status) << "a frame 150 ms of link time apart was dropped";

  // 5 ticks but 250 ms of link time between the halves: dropped, as on the controller.
  rig.host.have_status = false;
  rig.link.rx.insert(rig.link.rx.end(), f.begin(), f.begin() + 3);
  run_with_link_time(rig, clock, 5, 250);
  rig.link.rx.insert(rig.link.rx.end(), f.begin() + 3, f.end());
  rig.run(5);
  EXPECT_FALSE(rig.host.have_status) << "a frame 250 ms of link time apart was taken";
}

TEST(AppLinkClock, TheLinkWatchdogCountsTheLinkClockNotTheTick) {
  ManualLinkClock clock;
  AppRig rig(1, &clock);
  ASSERT_TRUE(rig.open_session());
  ASSERT_TRUE(rig.zero_here());
  rig.host.queue(proto::FeedMoveCmd{100000, 0, 2000});
  ASSERT_TRUE(rig.run_until([&] { return rig.app.state() == MachineState::kRunning; }, 2000));
  run_with_link_time(rig, clock, 20, 20);  // the host's last poll arrives
  // The host falls silent: 3 s of ticks, 1.5 s of link time: still running.
  for (int i = 0; i < 3000; ++i) {
    if (i % 2 == 0) ++clock.ms;
    rig.app.tick_1ms();
    rig.plant.step_1ms();
    rig.app.poll();
  }
  EXPECT_EQ(rig.app.state(), MachineState::kRunning);
  // 0.6 s more of both: 2.1 s of link silence hold the machine.
  for (int i = 0; i < 600; ++i) {
    ++clock.ms;
    rig.app.tick_1ms();
    rig.plant.step_1ms();
    rig.app.poll();
  }
  EXPECT_TRUE(rig.app.state() == MachineState::kHolding || rig.app.state() == MachineState::kHeld)
      << "state " << static_cast<int>(rig.app.state());
}

}  // namespace
}  // namespace fake_app
