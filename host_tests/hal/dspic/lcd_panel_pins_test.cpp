// The LCD bus on LATD and the panel contacts on PORTB, end to end: the HD44780 driver over
// the port's pins, decoded from the fake LATD writes by a simulated controller.
#include <gtest/gtest.h>

#include "hal/drivers/hd44780/hd44780.h"
#include "hal/dspic30f6014/lcd_pins.h"
#include "hal/dspic30f6014/panel_pins.h"
#include "hal/dspic30f6014/ports.h"
#include "hal/fake/panel/fake_hd44780.h"
#include "hal/interfaces/operator_inputs.h"
#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

// Feeds every LATD write into the model: RD0..7 data, RD8 RS, RD9 R/W, RD10 E. Busy-wait
// cycles since the previous write become model time (20 cycles per microsecond).
class LcdOnLatd : public FakeSfrTest {
 protected:
  LcdOnLatd() : seen_cycles(0) {
    dspic::init_ports();
    sfr.on_write = [this](uint16_t address, uint16_t value) {
      if (address != kLATD) return;
      const uint64_t cycles = sfr.delay_cycles();
      model.delay_us((uint16_t)((cycles - seen_cycles) / 20));
      seen_cycles = cycles;
      model.set_data((uint8_t)value);
      model.set_control((uint8_t)((value >> 8) & 7));
    };
  }
  fake::Hd44780Model model;
  uint64_t seen_cycles;
  dspic::LcdPins pins;
};

TEST_F(LcdOnLatd, DriverOverPortPinsShowsText) {
  drivers::Hd44780 lcd(&pins);
  lcd.init();
  lcd.write_line(0, "ENGRAVER v0.1");
  lcd.write_line(1, "TMC428 OK");
  EXPECT_EQ(model.visible_line(0), "ENGRAVER v0.1   ");
  EXPECT_EQ(model.visible_line(1), "TMC428 OK       ");
  EXPECT_TRUE(model.initialised_by_instruction());
  EXPECT_TRUE(model.violations().empty()) << model.violations().front();
}

TEST_F(LcdOnLatd, ControlLinesAreRd8ToRd10) {
  pins.set_control(hal::LcdBus::kRs | hal::LcdBus::kE);
  EXPECT_EQ(sfr.peek(kLATD) & 0x0700, 0x0500);
  pins.set_control(hal::LcdBus::kRw);
  EXPECT_EQ(sfr.peek(kLATD) & 0x0700, 0x0200);
}

TEST_F(LcdOnLatd, DataWriteLeavesTheHighByteAlone) {
  pins.set_control(hal::LcdBus::kRs);
  pins.set_data(0xA5);
  EXPECT_EQ(sfr.peek(kLATD), 0x01A5);
}

TEST_F(LcdOnLatd, DelayIsTwentyCyclesPerMicrosecond) {
  pins.delay_us(50);
  EXPECT_EQ(sfr.delay_cycles(), 1000u);
}

class PanelPinsTest : public FakeSfrTest {};

TEST_F(PanelPinsTest, OpenContactsReadAsNothingPressed) {
  sfr.poke(kPORTB, 0xFFFF);
  dspic::PanelPins pins;
  EXPECT_EQ(pins.read_raw(), 0);
}

TEST_F(PanelPinsTest, ContactPullingRb8LowIsJoystickLeft) {
  sfr.poke(kPORTB, (uint16_t)~0x0100);
  dspic::PanelPins pins;
  EXPECT_EQ(pins.read_raw(), hal::kJoyLeft);
}

TEST_F(PanelPinsTest, Rb14IsClearAndRb12IsZ) {
  sfr.poke(kPORTB, (uint16_t) ~(0x4000 | 0x1000));
  dspic::PanelPins pins;
  EXPECT_EQ(pins.read_raw(), hal::kButtonClear | hal::kButtonZ);
}

TEST_F(PanelPinsTest, OtherPortBPinsAreIgnored) {
  sfr.poke(kPORTB, 0x80FF & 0x0000);  // RB0..RB7 and RB15 low too
  dspic::PanelPins pins;
  EXPECT_EQ(pins.read_raw(), 0x7F);
}

}  // namespace
