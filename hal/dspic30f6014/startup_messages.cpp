// Start-up messages, each at most 16 characters (one LCD row).
#include "hal/dspic30f6014/startup_messages.h"

#include "hal/dspic30f6014/interrupts.h"  // TrapCause
#include "hal/dspic30f6014/registers.h"   // RCONbits

namespace dspic {

// A trap outranks the RCON flags (a trap reset also sets TRAPR).
const char* startup_line(uint8_t trap_cause, uint16_t reset_cause) {
  switch (trap_cause) {
    case kTrapOscillatorFail:
      return "RESET: OSC FAIL";
    case kTrapAddressError:
      return "RESET: ADDR TRAP";
    case kTrapStackError:
      return "RESET: STACK";
    case kTrapMathError:
      return "RESET: MATH TRAP";
    default:
      break;
  }
  if (reset_cause & bit(RCONbits::TRAPR)) return "RESET: TRAP";
  if (reset_cause & bit(RCONbits::WDTO)) return "RESET: WATCHDOG";
  if ((reset_cause & bit(RCONbits::BOR)) && !(reset_cause & bit(RCONbits::POR)))
    return "RESET: BROWNOUT";
  return "ENGRAVER 0.1";
}

// Indexed by the code, as drivers::Tmc428InitResult numbers them (one table, no switch).
const char* const kTmc428Lines[] = {"TMC428 OK",       "TMC428 E1 CONFIG", "TMC428 E2 NO ANS",
                                    "TMC428 E3 REG",   "TMC428 E4 RAM",    "TMC428 E5 CHAIN",
                                    "TMC428 E6 DRIVER"};

const char* tmc428_line(uint8_t init_result) {
  if (init_result < sizeof kTmc428Lines / sizeof kTmc428Lines[0]) return kTmc428Lines[init_result];
  return init_result == kSpiClockFailed ? "SPI CLOCK ERROR" : "TMC428 E? UNKNWN";
}

}  // namespace dspic
