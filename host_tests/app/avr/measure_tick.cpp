// AVR (ATmega2560 in simavr) measurement: cycles of one path-controller tick
// (app::PathController::tick, no SPI) and of one planner push, on a 10 mm/s circle with a
// simple integer plant. Prints over UART0. Build and run: docs/performance.md.
#include <avr/interrupt.h>  // cli
#include <avr/io.h>         // TCCR1B, TCNT1, UCSR0A, UDR0
#include <avr/sleep.h>      // sleep_cpu
#include <stdio.h>          // printf

#include "firmware/app/axis_scaling.h"     // build_axis_scaling
#include "firmware/app/coordinate_ring.h"  // CoordinateRing
#include "firmware/app/path_controller.h"  // PathController
#include "firmware/app/planner.h"          // Planner

static int uart_putchar(char c, FILE*) {
  while (!(UCSR0A & _BV(UDRE0))) {
  }
  UDR0 = (uint8_t)c;
  return 0;
}

// The reference chip as the driver reports it: 38.15 usteps/s per unit, a_max 13 units/ms.
class RefChip : public hal::MotionAxes {
 public:
  bool read_actual_usteps(int32_t*) { return true; }
  bool write_velocity_units(const int16_t*) { return true; }
  bool read_velocity_units(int16_t*) { return true; }
  bool set_actual_usteps(const int32_t*) { return true; }
  bool read_limits(uint8_t*) { return true; }
  uint32_t usteps_per_s_per_unit_q16(uint8_t) const { return 2500000UL; }
  int16_t max_velocity_units(uint8_t) const { return 2047; }
  uint16_t accel_units_per_ms(uint8_t a) const { return a == 2 ? 3 : 13; }
};

static FILE g_uart;
static RefChip g_chip;
static app::AxisScaling g_scaling;
static app::Planner g_planner;
static app::CoordinateRing g_ring;
static app::PathController g_controller;

// Circle of radius 20 mm about (40, 40) mm, 128 points (about 1 mm apart).
static void point(uint16_t i, int32_t out[3]) {
  // Quarter-wave table free: a 128-gon via the rotation recurrence in Q30 would cost more
  // code than this; a coarse integer octagon-free approximation is enough for timing.
  static const int16_t kSin[33] = {0,     1608,  3212,  4808,  6393,  7962,  9512,  11039, 12540,
                                   14010, 15447, 16846, 18205, 19520, 20788, 22006, 23170, 24279,
                                   25330, 26320, 27246, 28106, 28899, 29622, 30274, 30853, 31357,
                                   31786, 32138, 32413, 32610, 32729, 32767};
  const uint16_t k = i % 128;
  const uint8_t q = (uint8_t)(k / 32), r = (uint8_t)(k % 32);
  int32_t s, c;
  if (q == 0) {
    s = kSin[r];
    c = kSin[32 - r];
  } else if (q == 1) {
    s = kSin[32 - r];
    c = -kSin[r];
  } else if (q == 2) {
    s = -kSin[r];
    c = -kSin[32 - r];
  } else {
    s = -kSin[32 - r];
    c = kSin[r];
  }
  out[0] = 40000L + (c * 20000L) / 32768L;
  out[1] = 40000L + (s * 20000L) / 32768L;
  out[2] = 0;
}

int main() {
  UCSR0A = _BV(U2X0);
  UBRR0 = 1;
  UCSR0B = _BV(TXEN0);
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
  fdev_setup_stream(&g_uart, uart_putchar, 0, _FDEV_SETUP_WRITE);
  stdout = &g_uart;
  TCCR1A = 0;
  TCCR1B = _BV(CS10);  // clk/1

  const bool ok = app::build_axis_scaling(config::default_machine_config(), g_chip, &g_scaling);
  g_planner.init(g_scaling, app::default_planner_settings(10));
  g_controller.init(g_scaling);
  int32_t start[3];
  point(0, start);
  g_planner.set_origin(start);
  // Plant: positions in usteps with 8 fraction bits, v = units * 38.15 usteps/s.
  int32_t pos_q8[3];
  for (uint8_t i = 0; i < 3; ++i) pos_q8[i] = app::um_to_usteps(g_scaling, i, start[i]) * 256L;

  uint16_t next = 1;
  uint32_t tick_sum = 0, push_sum = 0;
  uint16_t tick_min = 0xFFFF, tick_max = 0, push_min = 0xFFFF, push_max = 0, pushes = 0;
  const uint16_t kTicks = 3000;
  uint16_t t0 = TCNT1;
  const uint16_t overhead = (uint16_t)(TCNT1 - t0);
  for (uint16_t t = 0; t < kTicks; ++t) {
    while (g_ring.free_space() > 0 && next < 400) {
      int32_t p[3];
      point(next, p);
      t0 = TCNT1;
      g_planner.push(&g_ring, p, 10000, 0, 0);
      const uint16_t c = (uint16_t)(TCNT1 - t0 - overhead);
      push_sum += c;
      ++pushes;
      if (c < push_min) push_min = c;
      if (c > push_max) push_max = c;
      ++next;
    }
    int32_t pos[3];
    for (uint8_t i = 0; i < 3; ++i) pos[i] = pos_q8[i] >> 8;
    int16_t v[3];
    t0 = TCNT1;
    g_controller.tick(pos, &g_ring, v);
    const uint16_t c = (uint16_t)(TCNT1 - t0 - overhead);
    tick_sum += c;
    if (c < tick_min) tick_min = c;
    if (c > tick_max) tick_max = c;
    // 1 ms of motion: v units * 38.15 usteps/s = v * 9.766 usteps/ms in Q8 (2500 / 256).
    for (uint8_t i = 0; i < 3; ++i) pos_q8[i] += (int32_t)v[i] * 9766L / 1000L;
  }
  printf("scaling_ok=%u ticks=%u speed=%u\n", ok ? 1U : 0U, kTicks, g_controller.speed_um_s());
  printf("tick_cycles min=%u avg=%lu max=%u\n", tick_min, tick_sum / kTicks, tick_max);
  printf("push_cycles min=%u avg=%lu max=%u n=%u\n", push_min, push_sum / pushes, push_max, pushes);
  printf("sizeof PathController=%u PlanEntry=%u\n", (unsigned)sizeof(app::PathController),
         (unsigned)sizeof(app::PlanEntry));
  while (!(UCSR0A & _BV(TXC0))) {
  }
  cli();
  sleep_enable();
  sleep_cpu();
  return 0;
}
