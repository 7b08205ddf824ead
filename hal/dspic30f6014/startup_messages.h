// The two LCD lines the firmware shows at power-up: the banner (or why the last reset
// happened, if it was not a normal one) and the TMC428 self-check result. docs/flashing.md
// lists every message.
#ifndef HAL_DSPIC30F6014_STARTUP_MESSAGES_H
#define HAL_DSPIC30F6014_STARTUP_MESSAGES_H

#include <stdint.h>  // uint8_t, uint16_t

namespace dspic {

enum { kStartupLineChars = 16, kSpiClockFailed = 0xFF };

// Row 0: "ENGRAVER 0.1" after power-on or MCLR; a trap (TrapCause) or a watchdog/brown-out
// reset (RCON bits from take_reset_cause()) is named instead.
const char* startup_line(uint8_t trap_cause, uint16_t reset_cause);
// Row 1: the TMC428 init result code (drivers::Tmc428InitResult as a number, 0 = ok) or
// kSpiClockFailed when SPI1 could not be set up.
const char* tmc428_line(uint8_t init_result);

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_STARTUP_MESSAGES_H
