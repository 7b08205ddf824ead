// Interrupt priorities, vector wiring and the trap record for the board.
//
// Priorities (1 lowest .. 7 highest; nesting enabled, NSTDIS = 0):
//   U1RX 6 > U1TX 5 > Timer1 4 > INT1 3 (probe); every other source 0 (disabled).
// Why RX above the tick: at 113 636 Bd a character arrives every 88 us and the hardware
// holds 4 (+1 in the shift register), ~0.4 ms. The 1 ms tick runs the path controller and
// several 26 us SPI datagrams, and may take a good part of its millisecond; RX must be able
// to interrupt it or a burst from the host overruns the FIFO. TX only refills the FIFO, so
// it can wait behind RX; it sits above the tick so replies keep the line busy. The probe's
// INT1 only remembers a touch for the tick, which reads it: below the tick, it can never
// change what the tick is reading.
#ifndef HAL_DSPIC30F6014_INTERRUPTS_H
#define HAL_DSPIC30F6014_INTERRUPTS_H

#include <stdint.h>  // uint8_t, uint16_t

#include "hal/dspic30f6014/platform.h"  // DSPIC_ISR

namespace dspic {

class Uart1;
class ProbePin;

enum {
  kU1RxPriority = 6,
  kU1TxPriority = 5,
  kTimer1Priority = 4,
  kProbePriority = 3,
  kIplMask = 0x00E0  // SR<7:5>
};

// Why the last reset happened, kept across the reset by the trap handlers.
enum TrapCause {
  kTrapNone = 0,
  kTrapOscillatorFail = 1,
  kTrapAddressError = 2,
  kTrapStackError = 3,
  kTrapMathError = 4
};

// Sets IPC0/IPC2 (and clears the other IPC registers' fields the board does not use) and
// enables nesting. Call before enabling any peripheral interrupt.
void configure_interrupt_priorities();
// What the vectors call. Set before the interrupts are enabled; 0 = ignore.
void install_uart1(Uart1* uart);
void install_tick(void (*tick)(void* context), void* context);
void install_probe(ProbePin* probe);
// The trap recorded before the last reset (kTrapNone after power-on), then forgets it.
uint8_t take_trap_cause();
// RCON reset-cause bits at start-up (POR, BOR, WDTO, SWR, EXTR, TRAPR), then clears them.
uint16_t take_reset_cause();

}  // namespace dspic

// The vectors (names from the XC16 vector table in p30F6014A.gld).
DSPIC_ISR(_T1Interrupt);
DSPIC_ISR(_U1RXInterrupt);
DSPIC_ISR(_U1TXInterrupt);
DSPIC_ISR(_INT1Interrupt);
DSPIC_ISR(_OscillatorFail);
DSPIC_ISR(_AddressError);
DSPIC_ISR(_StackError);
DSPIC_ISR(_MathError);

#endif  // HAL_DSPIC30F6014_INTERRUPTS_H
