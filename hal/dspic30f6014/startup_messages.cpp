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

// Codes as drivers::Tmc428InitResult numbers them.
const char* tmc428_line(uint8_t init_result) {
  switch (init_result) {
    case 0:
      return "TMC428 OK";
    case 1:
      return "TMC428 E1 CONFIG";
    case 2:
      return "TMC428 E2 NO ANS";
    case 3:
      return "TMC428 E3 REG";
    case 4:
      return "TMC428 E4 RAM";
    case 5:
      return "TMC428 E5 CHAIN";
    case 6:
      return "TMC428 E6 DRIVER";
    case kSpiClockFailed:
      return "SPI CLOCK ERROR";
    default:
      return "TMC428 E? UNKNWN";
  }
}

}  // namespace dspic
