// What the controller does with a feed hold (#H) during a probe (#Y), as docs/protocol.md
// says: Z stops where it is, going down (#R goes on down to the contact) or at the contact
// (the retract waits for #R). This is why a host that pauses probing for its operator sends
// no #H while a touch runs (engraver serve waits for the touch to end retracted).
#include <gtest/gtest.h>

#include "host/lib/heightmap/controller_map.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_machine.h"
#include "host_tests/host/sim/cut_link.h"

namespace host::heightmap {
namespace {

const int32_t kCopperUm = -50;  // a flat blank 50 um below the zero

struct Rig {
  Rig() {
    sim::SimOptions o;
    o.surface_um = [](int32_t, int32_t) { return kCopperUm; };
    machine = std::make_unique<sim::SimMachine>(o);
    SenderOptions so;
    so.clock = [this] { return sim::machine_clock(*machine); };
    link = std::make_unique<sim::SimLink>(*machine);
    sender = std::make_unique<Sender>(*link, so);
    sender->open_session();
  }
  std::unique_ptr<sim::SimMachine> machine;
  std::unique_ptr<sim::SimLink> link;
  std::unique_ptr<Sender> sender;
};

// One touch at (5, 5) mm; `hold_when` says (from the machine) when to hold; the hold is
// kept for 30 statuses, where the tool stood then is returned, then resumed.
struct HeldTouch {
  double held_z_mm = -1;
  bool held_z_moved = false;
  double contact_um = 0;
};

HeldTouch touch_held(Rig& rig, const std::function<bool()>& hold_when) {
  HeldTouch out;
  int held_statuses = 0;
  bool asked = false, resumed = false;
  // Asked as the tool moves (every millisecond of the machine), sent within a few.
  rig.machine->set_sample_sink([&](const sim::ToolSample&) {
    if (!asked && hold_when()) {
      rig.sender->request_hold();
      asked = true;
    }
  });
  auto on_progress = [&](const Progress& p) {
    if (asked && !resumed && p.status.state == proto::MachineState::kHeld) {
      const double z = rig.machine->position().z_mm;
      if (held_statuses == 0) out.held_z_mm = z;
      if (z != out.held_z_mm) out.held_z_moved = true;
      if (++held_statuses == 30) {
        rig.sender->request_resume();
        resumed = true;
      }
    }
  };
  out.contact_um = controller_touch(*rig.sender, ProbeMotion{}, on_progress)(5, 5);
  EXPECT_TRUE(resumed) << "never held";
  return out;
}

TEST(ProbeHoldSim, AHoldGoingDownStopsZAboveTheCopperAndResumeGoesOnToTheContact) {
  Rig rig;
  const HeldTouch t = touch_held(rig, [&] {
    const sim::ToolSample s = rig.machine->position();
    return s.x_mm > 4.99 && s.z_mm < 0.5;  // over the point, going down
  });
  EXPECT_GT(t.held_z_mm, kCopperUm / 1000.0 + 0.4);
  EXPECT_LT(t.held_z_mm, 0.5);
  EXPECT_FALSE(t.held_z_moved);
  EXPECT_NEAR(t.contact_um, kCopperUm, 3);
  EXPECT_NEAR(rig.machine->position().z_mm, kCopperUm / 1000.0 + ProbeMotion{}.retract_mm, 0.005);
}

TEST(ProbeHoldSim, AHoldAtTheContactKeepsTheToolOnTheCopperUntilResume) {
  Rig rig;
  const HeldTouch t = touch_held(rig, [&] { return rig.machine->probe_closed(); });
  EXPECT_NEAR(t.held_z_mm, kCopperUm / 1000.0, 0.015) << "the retract waits for #R";
  EXPECT_FALSE(t.held_z_moved);
  EXPECT_NEAR(rig.machine->position().z_mm, kCopperUm / 1000.0 + ProbeMotion{}.retract_mm, 0.005);
}

// Issue 25's workshop tester: a link cut for over 2 s (the controller's link watchdog holds
// the touch where it is) left the sender waiting out its stall limit, and the probing failed.
// When the link is back the touch goes on (#R) to the contact and retracts, the same height.
TEST(ProbeHoldSim, ALinkCutGoingDownHoldsTheTouchAndItGoesOnWhenTheLinkIsBack) {
  sim::SimOptions o;
  o.surface_um = [](int32_t, int32_t) { return kCopperUm; };
  sim::SimMachine machine(o);
  test::CutLink link(machine);
  SenderOptions so;
  so.clock = [&machine] { return sim::machine_clock(machine); };
  Sender sender(link, so);
  sender.open_session();
  ProbeMotion slow;  // down at 0.2 mm/s: from Z 0.5 mm the copper is over 2 s away
  slow.feed_mm_s = 0.2;
  bool cut = false, held = false;
  machine.set_sample_sink([&](const sim::ToolSample& s) {
    if (!cut && s.x_mm > 4.99 && s.z_mm < 0.5) {  // over the point, going down
      link.cut_for(3000);
      cut = true;
    }
  });
  const double contact_um = controller_touch(sender, slow, [&](const Progress& p) {
    if (p.status.flags & proto::kStatusLinkHold) held = true;
  })(5, 5);
  EXPECT_TRUE(cut);
  EXPECT_TRUE(held) << "the cut was not long enough to hold the touch";
  EXPECT_EQ(sender.stats().link_hold_resumes, 1u);
  EXPECT_NEAR(contact_um, kCopperUm, 3);
  EXPECT_NEAR(machine.position().z_mm, kCopperUm / 1000.0 + ProbeMotion{}.retract_mm, 0.005);
}

}  // namespace
}  // namespace host::heightmap
