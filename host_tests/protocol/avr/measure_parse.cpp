// AVR (ATmega2560 in simavr) measurement: cycles to parse and decode one full #D frame
// (64-byte payload), one byte at a time, and the CRC share. Prints over UART0.
// Build and run: see docs/performance.md "Path controller and protocol".
#include <avr/interrupt.h>  // cli
#include <avr/io.h>         // TCCR1B, TCNT1, UCSR0A, UDR0
#include <avr/sleep.h>      // sleep_cpu
#include <stdio.h>          // printf

#include "firmware/protocol/codec.h"   // write_frame, decode_frame
#include "firmware/protocol/crc16.h"   // crc16
#include "firmware/protocol/parser.h"  // Parser

static int uart_putchar(char c, FILE*) {
  while (!(UCSR0A & _BV(UDRE0))) {
  }
  UDR0 = (uint8_t)c;
  return 0;
}

static FILE g_uart;
static uint8_t g_frame[proto::kMaxFrameBytes];
static uint8_t g_size;

// A #D with 4 control points and 5 knots: 4 + 40 + 20 = 64 payload bytes, 70 frame bytes.
static void build_frame() {
  proto::SplineDataCmd d;
  d.control_index = 0;
  d.control_n = 4;
  d.knot_index = 0;
  d.knot_n = 5;
  for (uint8_t i = 0; i < 4; ++i) {
    d.control[i].x_um = 123456L * (i + 1);
    d.control[i].y_um = -98765L * (i + 1);
    d.control[i].weight_q14 = 16384U;
  }
  for (uint8_t i = 0; i < 5; ++i) d.knot[i] = 1000L * i;
  proto::write_frame(d, 7, g_frame, sizeof g_frame, &g_size);
}

int main() {
  UCSR0A = _BV(U2X0);
  UBRR0 = 1;
  UCSR0B = _BV(TXEN0);
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
  fdev_setup_stream(&g_uart, uart_putchar, 0, _FDEV_SETUP_WRITE);
  stdout = &g_uart;
  TCCR1A = 0;
  TCCR1B = _BV(CS10);  // clk/1: TCNT1 counts CPU cycles (all runs below fit 16 bits)
  build_frame();

  static proto::Parser parser(proto::kCommandStart);
  proto::SplineDataCmd decoded;
  uint16_t ok = 0;

  uint16_t t0 = TCNT1;
  for (uint8_t i = 0; i < g_size; ++i) {
    if (parser.feed(g_frame[i]) == proto::ParseEvent::kFrame) ++ok;
  }
  uint16_t parse_cycles = (uint16_t)(TCNT1 - t0);

  t0 = TCNT1;
  const proto::ErrorCode e = proto::decode_frame(parser.frame(), &decoded);
  uint16_t decode_cycles = (uint16_t)(TCNT1 - t0);

  t0 = TCNT1;
  volatile uint16_t crc = proto::crc16(g_frame, (size_t)(g_size - 2));
  uint16_t crc_cycles = (uint16_t)(TCNT1 - t0);
  (void)crc;

  t0 = TCNT1;
  uint16_t empty = (uint16_t)(TCNT1 - t0);

  printf("frame_bytes=%u frames=%u decode=%u\n", g_size, ok, (unsigned)e);
  printf("parse_cycles=%u decode_cycles=%u crc_cycles=%u timer_overhead=%u\n", parse_cycles,
         decode_cycles, crc_cycles, empty);
  printf("parser_ram_bytes=%u\n", (unsigned)sizeof(proto::Parser));
  while (!(UCSR0A & _BV(TXC0))) {
  }
  cli();
  sleep_enable();
  sleep_cpu();
  return 0;
}
