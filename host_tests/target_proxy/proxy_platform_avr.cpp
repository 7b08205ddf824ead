// The proxy platform on an ATmega2560 (run in simavr): UART0 for text, Timer1 for cycles.
#include "host_tests/target_proxy/proxy_platform.h"

#include <avr/interrupt.h>  // ISR, cli, sei
#include <avr/io.h>         // UCSR0A, UDR0, TCCR1B, TCNT1, TIFR1, RAMEND
#include <avr/sleep.h>      // sleep_enable, sleep_cpu

extern "C" char __heap_start;  // end of .data + .bss (avr-libc linker script)
extern "C" char __data_start;  // start of .data (= start of RAM in use)

namespace proxy {

namespace {

const uint8_t kPaint = 0xA5;
volatile uint16_t g_timer1_overflows;
uint32_t g_overhead;

// Blocking write of one byte to UART0 (FILE stream hook for printf).
int uart_putchar(char c, FILE*) {
  while (!(UCSR0A & _BV(UDRE0))) {
  }
  UDR0 = (uint8_t)c;
  return 0;
}

FILE g_uart_stream;

// Fills the free RAM between the static data and the current stack with kPaint.
void paint_stack() {
  uint8_t* p = (uint8_t*)&__heap_start;
  uint8_t* sp = (uint8_t*)SP;
  while (p < sp - 16) *p++ = kPaint;
}

}  // namespace

}  // namespace proxy

// Extends Timer1 to 32 bits.
ISR(TIMER1_OVF_vect) {
  ++proxy::g_timer1_overflows;
}

namespace proxy {

void platform_init() {
  paint_stack();
  // 1 Mbaud (U2X, UBRR 1 at 16 MHz): simavr models the byte time, so fast is cheaper.
  UCSR0A = _BV(U2X0);
  UBRR0 = 1;
  UCSR0B = _BV(TXEN0);
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
  fdev_setup_stream(&g_uart_stream, uart_putchar, 0, _FDEV_SETUP_WRITE);
  stdout = &g_uart_stream;
  // Timer1: normal mode, clk/1, overflow interrupt.
  TCCR1A = 0;
  TCCR1B = _BV(CS10);
  TIMSK1 = _BV(TOIE1);
  sei();
  uint32_t best = 0xFFFFFFFFUL;
  for (uint8_t i = 0; i < 8; ++i) {
    const uint32_t a = cycles_now();
    const uint32_t b = cycles_now();
    if (b - a < best) best = b - a;
  }
  g_overhead = best;
}

uint32_t cycles_now() {
  const uint8_t sreg = SREG;
  cli();
  const uint16_t low = TCNT1;
  uint16_t high = g_timer1_overflows;
  // An overflow not yet serviced (interrupts are off) belongs before a small low word.
  if ((TIFR1 & _BV(TOV1)) && low < 0x8000U) ++high;
  SREG = sreg;
  return ((uint32_t)high << 16) | low;
}

uint32_t cycles_overhead() {
  return g_overhead;
}

uint32_t counter_hz() {
  return F_CPU;
}

const char* counter_unit() {
  return "cycles";
}

uint16_t stack_peak_bytes() {
  const uint8_t* p = (const uint8_t*)&__heap_start;
  while (p <= (const uint8_t*)RAMEND && *p == kPaint) ++p;
  return (uint16_t)((const uint8_t*)RAMEND + 1 - p);
}

uint16_t static_ram_bytes() {
  return (uint16_t)(&__heap_start - &__data_start);
}

void platform_finish(bool) {
  // Let the last byte leave the UART, then sleep with interrupts off: simavr stops.
  while (!(UCSR0A & _BV(TXC0)) && (UCSR0B & _BV(TXEN0))) {
  }
  cli();
  sleep_enable();
  sleep_cpu();
  for (;;) {
  }
}

}  // namespace proxy
