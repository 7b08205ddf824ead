// Firmware entry on the dsPIC30F6014: brings up the ports, LCD, panel, UART1 (XPort),
// SPI1 + TMC428, shows the start-up result, then runs the application: Timer1's 1 ms tick
// samples the panel and runs app::Application::tick_1ms(), the main loop runs poll().
#include <stdint.h>  // uint8_t, uint16_t

#include "firmware/app/application.h"                   // app::Application, app::Board
#include "firmware/config/machine_config.h"             // config::default_machine_config
#include "hal/drivers/hd44780/hd44780.h"                // drivers::Hd44780
#include "hal/drivers/operator_panel/operator_panel.h"  // drivers::OperatorPanel
#include "hal/drivers/tmc428/tmc428.h"                  // drivers::Tmc428
#include "hal/dspic30f6014/interrupts.h"  // priorities, install_*, take_*_cause
#include "hal/dspic30f6014/lcd_pins.h"    // dspic::LcdPins
#include "hal/dspic30f6014/panel_pins.h"  // dspic::PanelPins
#include "hal/dspic30f6014/ports.h"       // dspic::init_ports
#include "hal/dspic30f6014/spi1.h"        // dspic::Spi1
#include "hal/dspic30f6014/startup_messages.h"  // dspic::startup_line, tmc428_line
#include "hal/dspic30f6014/timer1.h"      // dspic::timer1_start_1ms
#include "hal/dspic30f6014/uart1.h"       // dspic::Uart1

namespace {

const uint32_t kHostBaud = 115200;  // 113 636 Bd at Fcy 20 MHz (-1.4 %), XPort 115200 8N1
const uint16_t kBannerHoldMs = 1500;

// Static storage so the linker's memory report counts them. Constructors run from the
// XC16++ start-up code; none of these has a destructor.
config::MachineConfig g_machine = config::default_machine_config();
dspic::LcdPins g_lcd_pins;
drivers::Hd44780 g_lcd(&g_lcd_pins);
dspic::PanelPins g_panel_pins;
drivers::OperatorPanel g_panel(&g_panel_pins, drivers::OperatorPanel::kZHeld,
                               drivers::OperatorPanel::kDefaultDebounceMs);
dspic::Uart1 g_uart;
dspic::Spi1 g_spi;
drivers::Tmc428 g_tmc(g_spi, g_machine);
app::Application g_app;

// Timer1 interrupt, priority 4: panel first so the application sees this millisecond's state.
void on_tick(void*) {
  g_panel.tick_1ms();
  g_app.tick_1ms();
}

// Busy-waits in 1 ms steps (only before the tick starts).
void wait_ms(uint16_t ms) {
  for (uint16_t i = 0; i < ms; ++i) dspic::delay_us(1000);
}

}  // namespace

int main() {
  const uint16_t reset_cause = dspic::take_reset_cause();
  const uint8_t trap_cause = dspic::take_trap_cause();
  dspic::init_ports();
  dspic::configure_interrupt_priorities();

  g_lcd.init();
  g_lcd.write_line(0, dspic::startup_line(trap_cause, reset_cause));

  g_uart.init(kHostBaud);
  dspic::install_uart1(&g_uart);

  uint8_t tmc_result = dspic::kSpiClockFailed;
  if (g_spi.init(g_machine.spi_clock_hz)) tmc_result = (uint8_t)g_tmc.init();
  g_lcd.write_line(1, dspic::tmc428_line(tmc_result));
  wait_ms(kBannerHoldMs);

  // A failed self-check leaves the TMC428 driver refusing motion; the application still
  // runs so the host can read the alarm.
  app::Board board;
  board.link = &g_uart;
  board.motion = &g_tmc;
  board.display = &g_lcd;
  board.inputs = &g_panel;
  g_app.init(board, g_machine);

  dspic::install_tick(on_tick, 0);
  dspic::timer1_start_1ms();
  for (;;) g_app.poll();
}
