// Start-up with the port's SPI1 under the TMC428 driver: what the operator reads on the LCD
// when the TMC428 is missing or the SPI bus is dead (docs/flashing.md, first power-up).
#include <gtest/gtest.h>

#include "firmware/config/machine_config.h"
#include "hal/drivers/hd44780/hd44780.h"
#include "hal/drivers/tmc428/tmc428.h"
#include "hal/dspic30f6014/lcd_pins.h"
#include "hal/dspic30f6014/ports.h"
#include "hal/dspic30f6014/spi1.h"
#include "hal/dspic30f6014/startup_messages.h"
#include "hal/fake/panel/fake_hd44780.h"
#include "host_tests/hal/dspic/fake_sfr_fixture.h"

namespace {

class BringUpTest : public FakeSfrTest {
 protected:
  BringUpTest() : machine(config::default_machine_config()), tmc(spi, machine) {
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
  // main()'s sequence for the two start-up rows.
  void bring_up() {
    drivers::Hd44780 lcd(&pins);
    lcd.init();
    lcd.write_line(0, dspic::startup_line(0, 0x0001));
    uint8_t result = dspic::kSpiClockFailed;
    if (spi.init(machine.spi_clock_hz)) result = (uint8_t)tmc.init();
    lcd.write_line(1, dspic::tmc428_line(result));
  }
  config::MachineConfig machine;
  dspic::Spi1 spi;
  drivers::Tmc428 tmc;
  dspic::LcdPins pins;
  fake::Hd44780Model model;
  uint64_t seen_cycles = 0;
};

TEST_F(BringUpTest, MissingTmc428ShowsNoAnswer) {
  bring_up();  // MISO reads all zeros
  EXPECT_EQ(model.visible_line(0), "ENGRAVER 0.1    ");
  EXPECT_EQ(model.visible_line(1), "TMC428 E2 NO ANS");
  EXPECT_FALSE(sfr.spi1_words().empty());
}

TEST_F(BringUpTest, DeadSpiBusShowsNoAnswerWithoutHanging) {
  sfr.set_spi1_stalled(true);
  bring_up();
  EXPECT_EQ(model.visible_line(1), "TMC428 E2 NO ANS");
  EXPECT_GT(spi.timeouts(), 0);
}

TEST_F(BringUpTest, EveryDatagramIsTwoWordsUnderChipSelect) {
  bring_up();
  const auto& words = sfr.spi1_words();
  ASSERT_EQ(words.size() % 2, 0u);
  for (const auto& w : words) EXPECT_TRUE(w.cs_low);
}

}  // namespace
