// The Z toggle button end to end below the application: the operator panel driver as the
// firmware builds it (OperatorPanel::kZHeld, hal/dspic30f6014/main.cpp) feeding the jog
// controller, which owns the toggle. One physical press, bounces included, is one toggle.
#include <gtest/gtest.h>

#include <cstdint>

#include "firmware/app/jog_controller.h"
#include "hal/drivers/operator_panel/operator_panel.h"
#include "hal/fake/panel/fake_panel_pins.h"

namespace {

class PanelAndJog {
 public:
  PanelAndJog()
      : panel_(&pins_, drivers::OperatorPanel::kZHeld, drivers::OperatorPanel::kDefaultDebounceMs) {
    app::AxisScaling scaling{};
    jog_.init(scaling);
    jog_.start(7, panel_.state());
  }
  // One 1 ms tick as in Application::tick_1ms: sample the panel, then run the jog.
  void tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      panel_.tick_1ms();
      int32_t pos[config::kAxisCount] = {0, 0, 0};
      int16_t v[config::kAxisCount] = {0, 0, 0};
      jog_.tick(panel_.state(), 0, pos, v);
    }
  }
  // Press the Z button for hold_ms (with contact bounce at both edges), then release it.
  void press_z(int hold_ms) {
    pins_.script({hal::kButtonZ, 0, hal::kButtonZ, 0});
    pins_.set(hal::kButtonZ);
    tick(hold_ms);
    pins_.script({0, hal::kButtonZ, 0});
    pins_.set(0);
    tick(20);
  }
  bool z_mode() const { return jog_.z_mode(); }

 private:
  fake::PanelPins pins_;
  drivers::OperatorPanel panel_;
  app::JogController jog_;
};

TEST(ZButton, FirstPressTurnsZModeOn) {
  PanelAndJog rig;
  rig.tick(10);
  ASSERT_FALSE(rig.z_mode());
  rig.press_z(50);
  EXPECT_TRUE(rig.z_mode());
}

TEST(ZButton, SecondPressTurnsZModeOff) {
  PanelAndJog rig;
  rig.press_z(50);
  rig.press_z(50);
  EXPECT_FALSE(rig.z_mode());
}

TEST(ZButton, ThreePressesLeaveZModeOn) {
  PanelAndJog rig;
  rig.press_z(50);
  rig.press_z(50);
  rig.press_z(50);
  EXPECT_TRUE(rig.z_mode());
}

TEST(ZButton, ALongPressIsStillOnePress) {
  PanelAndJog rig;
  rig.press_z(2000);
  EXPECT_TRUE(rig.z_mode());
}

}  // namespace
