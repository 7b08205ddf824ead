// Firmware entry on the dsPIC30F6014: brings up the ports, LCD, panel, UART1 (XPort),
// SPI1 + TMC428, shows the start-up result, then runs the application: Timer1's 1 ms tick
// samples the panel and runs app::Application::tick_1ms(), the main loop runs poll().
#include <stdint.h>  // uint8_t, uint16_t

// app::Application is concrete but derives from an interface (never deleted through it).
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
#include "firmware/app/application.h"  // app::Application, app::Board
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif
#include "firmware/config/machine_config.h"             // config::default_machine_config
#include "firmware/runtime/placement_new.h"             // operator new(size_t, void*, InPlace)
#include "hal/drivers/hd44780/hd44780.h"                // drivers::Hd44780
#include "hal/drivers/operator_panel/operator_panel.h"  // drivers::OperatorPanel
#include "hal/drivers/tmc428/tmc428.h"                  // drivers::Tmc428
#include "hal/dspic30f6014/clock.h"                     // dspic::delay_us
#include "hal/dspic30f6014/interrupts.h"                // priorities, install_*, take_*_cause
#include "hal/dspic30f6014/lcd_pins.h"                  // dspic::LcdPins
#include "hal/dspic30f6014/panel_pins.h"                // dspic::PanelPins
#include "hal/dspic30f6014/ports.h"                     // dspic::init_ports
#include "hal/dspic30f6014/probe_pin.h"                 // dspic::ProbePin
#include "hal/dspic30f6014/spi1.h"                      // dspic::Spi1
#include "hal/dspic30f6014/spindle_pin.h"               // dspic::SpindlePin
#include "hal/dspic30f6014/startup_messages.h"          // dspic::startup_line, tmc428_line
#include "hal/dspic30f6014/timer1.h"                    // dspic::timer1_start_1ms
#include "hal/dspic30f6014/uart1.h"                     // dspic::Uart1

namespace {

const uint32_t kHostBaud = 115200;  // 113 636 Bd at Fcy 20 MHz (-1.4 %), XPort 115200 8N1
const uint16_t kBannerHoldMs = 1500;

// Static storage for one object, constructed in main() with placement new: the objects
// then live in .bss (counted by the linker's memory report) without global constructors,
// and nothing ever needs their (interface-inherited, non-trivial) destructors.
template <typename T>
class Slot {
 public:
  void* place() { return storage_.bytes; }

 private:
  // The union aligns the bytes for any member T can have (a misaligned word access is an
  // address-error trap on the dsPIC); no dependent alignment attribute needed.
  union {
    uint8_t bytes[sizeof(T)];
    uint64_t align_integer;
    void* align_pointer;
  } storage_;
};

Slot<config::MachineConfig> g_machine_slot;
Slot<dspic::LcdPins> g_lcd_pins_slot;
Slot<drivers::Hd44780> g_lcd_slot;
Slot<dspic::PanelPins> g_panel_pins_slot;
Slot<drivers::OperatorPanel> g_panel_slot;
Slot<dspic::Uart1> g_uart_slot;
Slot<dspic::Spi1> g_spi_slot;
Slot<dspic::SpindlePin> g_spindle_slot;
Slot<dspic::ProbePin> g_probe_slot;
Slot<drivers::Tmc428> g_tmc_slot;
Slot<app::Application> g_app_slot;

// Set in main() before the Timer1 interrupt is enabled, only read by on_tick().
drivers::OperatorPanel* g_panel = 0;
app::Application* g_app = 0;

// Timer1 interrupt, priority 4: panel first so the application sees this millisecond's state.
void on_tick(void*) {
  g_panel->tick_1ms();
  g_app->tick_1ms();
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

  config::MachineConfig* machine = new (g_machine_slot.place(), core::InPlace())
      config::MachineConfig(config::default_machine_config());
  dspic::LcdPins* lcd_pins = new (g_lcd_pins_slot.place(), core::InPlace()) dspic::LcdPins();
  drivers::Hd44780* lcd = new (g_lcd_slot.place(), core::InPlace()) drivers::Hd44780(lcd_pins);
  dspic::PanelPins* panel_pins =
      new (g_panel_pins_slot.place(), core::InPlace()) dspic::PanelPins();
  // kZHeld: the Z button is passed on as pressed/released; the application toggles Z mode.
  g_panel = new (g_panel_slot.place(), core::InPlace()) drivers::OperatorPanel(
      panel_pins, drivers::OperatorPanel::kZHeld, drivers::OperatorPanel::kDefaultDebounceMs);
  dspic::Uart1* uart = new (g_uart_slot.place(), core::InPlace()) dspic::Uart1();
  dspic::Spi1* spi = new (g_spi_slot.place(), core::InPlace()) dspic::Spi1();
  dspic::SpindlePin* spindle = new (g_spindle_slot.place(), core::InPlace()) dspic::SpindlePin();
  dspic::ProbePin* probe = new (g_probe_slot.place(), core::InPlace()) dspic::ProbePin();
  drivers::Tmc428* tmc = new (g_tmc_slot.place(), core::InPlace()) drivers::Tmc428(*spi, *machine);
  g_app = new (g_app_slot.place(), core::InPlace()) app::Application();

  lcd->init();
  lcd->write_line(0, dspic::startup_line(trap_cause, reset_cause));

  uart->init(kHostBaud);
  dspic::install_uart1(uart);

  uint8_t tmc_result = dspic::kSpiClockFailed;
  if (spi->init(machine->spi_clock_hz)) tmc_result = (uint8_t)tmc->init();
  lcd->write_line(1, dspic::tmc428_line(tmc_result));
  wait_ms(kBannerHoldMs);

  // A failed self-check leaves the TMC428 driver refusing motion; the application still
  // runs so the host can read the alarm.
  app::Board board;
  board.link = uart;
  board.motion = tmc;
  board.display = lcd;
  board.inputs = g_panel;
  board.spindle = spindle;
  board.link_clock = 0;  // the 1 ms tick is wall-clock time: the link's time-outs count it
  board.probe = probe;
  g_app->init(board, *machine);

  dspic::install_probe(probe);
  probe->init();

  dspic::install_tick(on_tick, 0);
  dspic::timer1_start_1ms();
  for (;;) g_app->poll();
}
