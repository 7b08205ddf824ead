// Operator panel: debouncing, joystick sanity, Z held/toggle.
#include "hal/drivers/operator_panel/operator_panel.h"

#include <gtest/gtest.h>

#include "hal/fake/panel/fake_panel_pins.h"

namespace {

void ticks(drivers::OperatorPanel& p, int n) {
  for (int i = 0; i < n; ++i) p.tick_1ms();
}

TEST(OperatorPanel, StartsWithNothingPressed) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 5);
  EXPECT_EQ(panel.state(), 0);
}

TEST(OperatorPanel, TakesAPressAfter5EqualSamples) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 5);
  pins.set(hal::kButtonConfirm);
  ticks(panel, 4);
  EXPECT_EQ(panel.state(), 0);
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), hal::kButtonConfirm);
}

TEST(OperatorPanel, BounceRestartsTheCount) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 5);
  const uint8_t c = hal::kButtonClear;
  pins.script({c, c, c, 0, c, c, c, c});  // bounce on the 4th sample
  pins.set(c);
  ticks(panel, 8);
  EXPECT_EQ(panel.state(), 0);  // only 4 equal samples since the bounce
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), c);
}

TEST(OperatorPanel, TakesAReleaseAfter5EqualSamples) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 5);
  pins.set(hal::kJoyLeft);
  ticks(panel, 5);
  pins.set(0);
  ticks(panel, 4);
  EXPECT_EQ(panel.state(), hal::kJoyLeft);
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), 0);
}

TEST(OperatorPanel, DebouncesEachContactOnItsOwn) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 5);
  pins.set(hal::kJoyUp);
  ticks(panel, 3);
  pins.set(hal::kJoyUp | hal::kButtonConfirm);
  ticks(panel, 2);
  EXPECT_EQ(panel.state(), hal::kJoyUp);
  ticks(panel, 3);
  EXPECT_EQ(panel.state(), hal::kJoyUp | hal::kButtonConfirm);
}

TEST(OperatorPanel, OppositeJoystickContactsCancel) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 1);
  pins.set(hal::kJoyLeft | hal::kJoyRight | hal::kJoyUp);
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), hal::kJoyUp);
  EXPECT_EQ(panel.contacts(), hal::kJoyLeft | hal::kJoyRight | hal::kJoyUp);
}

TEST(OperatorPanel, HeldZModeReportsZOnlyWhileHeld) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 1);
  pins.set(hal::kButtonZ | hal::kJoyDown);
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), hal::kButtonZ | hal::kJoyDown);
  pins.set(hal::kJoyDown);
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), hal::kJoyDown);
}

TEST(OperatorPanel, ToggleZModeFlipsOnEachPress) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZToggle, 2);
  pins.set(hal::kButtonZ);
  ticks(panel, 2);
  pins.set(0);
  ticks(panel, 2);
  EXPECT_EQ(panel.state(), hal::kButtonZ);  // released, still in Z mode
  pins.set(hal::kButtonZ);
  ticks(panel, 2);
  pins.set(0);
  ticks(panel, 2);
  EXPECT_EQ(panel.state(), 0);
}

TEST(OperatorPanel, ToggleIgnoresBounceShorterThanTheDebounce) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZToggle, 3);
  pins.script({hal::kButtonZ, hal::kButtonZ, 0, hal::kButtonZ, hal::kButtonZ, 0});
  ticks(panel, 6);
  EXPECT_EQ(panel.state(), 0);
}

TEST(OperatorPanel, ZeroDebounceCountsAsOneSample) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 0);
  pins.set(hal::kButtonClear);
  ticks(panel, 1);
  EXPECT_EQ(panel.state(), hal::kButtonClear);
}

TEST(OperatorPanel, SamplesOncePerTick) {
  fake::PanelPins pins;
  drivers::OperatorPanel panel(&pins, drivers::OperatorPanel::kZHeld, 5);
  ticks(panel, 7);
  panel.state();
  EXPECT_EQ(pins.reads(), 7);
}

}  // namespace
