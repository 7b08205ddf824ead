// What the target-proxy checks need from the machine they run on: text output, a cycle
// counter, read-only tables in flash, a stack high-water mark and a way to stop. One
// implementation for the AVR in simavr (proxy_platform_avr.cpp), one for the host.
#ifndef HOST_TESTS_TARGET_PROXY_PROXY_PLATFORM_H
#define HOST_TESTS_TARGET_PROXY_PROXY_PLATFORM_H

#include <stdint.h>  // uint32_t
#include <stdio.h>   // printf, printf_P
#include <string.h>  // memcpy

#ifdef __AVR__
#include <avr/pgmspace.h>  // PROGMEM, PSTR, memcpy_P, printf_P
// Tables live in flash (RAM is 8 KB); text too.
#define PROXY_ROM PROGMEM
#define PROXY_ROM_COPY(dst, src, n) memcpy_P((dst), (src), (n))
#define PROXY_PRINTF(fmt, ...) printf_P(PSTR(fmt), ##__VA_ARGS__)
#define PROXY_STR(s) PSTR(s)
#define PROXY_PRINT_STR(s) printf_P(PSTR("%S"), (s))
#else
#define PROXY_ROM
#define PROXY_ROM_COPY(dst, src, n) memcpy((dst), (src), (n))
#define PROXY_PRINTF(fmt, ...) printf(fmt, ##__VA_ARGS__)
#define PROXY_STR(s) (s)
#define PROXY_PRINT_STR(s) printf("%s", (s))
#endif

namespace proxy {

// Sets up output and the cycle counter; paints free RAM for the stack high-water mark.
void platform_init();

// Cycle counter (AVR: Timer1 at clk/1 extended by its overflow interrupt; host: ns).
uint32_t cycles_now();
// Cost of an empty cycles_now() pair, subtracted by measurements.
uint32_t cycles_overhead();
// Counter ticks per second (AVR: F_CPU; host: 1e9).
uint32_t counter_hz();
// "cycles" on the AVR, "ns" on the host.
const char* counter_unit();

// Bytes of stack used so far (AVR: deepest painted byte overwritten; host: 0).
uint16_t stack_peak_bytes();
// Bytes of static RAM (.data + .bss; AVR only, host: 0).
uint16_t static_ram_bytes();

// Ends the run (AVR: sleep with interrupts off, which stops simavr; host: exit status).
void platform_finish(bool all_passed);

}  // namespace proxy

#endif  // HOST_TESTS_TARGET_PROXY_PROXY_PLATFORM_H
