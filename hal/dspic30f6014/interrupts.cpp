// Interrupt priorities, the vectors, the trap handlers and hal::irq_save/irq_restore.
#include "hal/dspic30f6014/interrupts.h"

#include "hal/dspic30f6014/probe_pin.h"  // ProbePin
#include "hal/dspic30f6014/registers.h"  // IPCx, INTCON1, IFS0, IFS1, SR, RCON
#include "hal/dspic30f6014/timer1.h"     // timer1_acknowledge
#include "hal/dspic30f6014/uart1.h"      // Uart1
#include "hal/interfaces/irq.h"          // hal::irq_save, hal::irq_restore

namespace dspic {

namespace {
// Written once by main before interrupts are enabled, then only read by the vectors.
Uart1* g_uart1 = 0;
void (*g_tick)(void*) = 0;
void* g_tick_context = 0;
ProbePin* g_probe = 0;

// A vector's work: the registered owner's handler, or with no owner the flag cleared (else
// the interrupt would fire again at once).
template <typename Owner, void (Owner::*kHandler)(), typename FlagRegister, uint8_t kFlag>
inline void serve(Owner* owner) {
  if (owner != 0) {
    (owner->*kHandler)();
  } else {
    FlagRegister::template clear_bit<kFlag>();
  }
}
}  // namespace

// Survives the reset a trap handler causes (not cleared by the start-up code).
DSPIC_PERSISTENT volatile uint8_t g_trap_cause;
DSPIC_PERSISTENT volatile uint8_t g_trap_check;  // ~g_trap_cause when g_trap_cause is valid

void configure_interrupt_priorities() {
  INTCON1::clear_bit<INTCON1bits::NSTDIS>();  // nesting: RX may interrupt the tick
  IPC0::write((uint16_t)(kTimer1Priority << IPC0bits::T1IP));
  IPC1::write(0);
  IPC2::write(
      (uint16_t)((kU1RxPriority << IPC2bits::U1RXIP) | (kU1TxPriority << IPC2bits::U1TXIP)));
  IPC4::write((uint16_t)(kProbePriority << IPC4bits::INT1IP));  // enabled by ProbePin::init
}

void install_uart1(Uart1* uart) {
  g_uart1 = uart;
}

void install_tick(void (*tick)(void*), void* context) {
  g_tick_context = context;
  g_tick = tick;
}

void install_probe(ProbePin* probe) {
  g_probe = probe;
}

uint8_t take_trap_cause() {
  uint8_t cause = kTrapNone;
  const uint8_t stored = g_trap_cause;
  const uint8_t check = (uint8_t)(stored ^ 0xFFu);
  if (check == g_trap_check) cause = stored;
  g_trap_cause = kTrapNone;
  g_trap_check = 0;
  return cause;
}

uint16_t take_reset_cause() {
  const uint16_t cause = RCON::read();
  const uint16_t flags =
      (uint16_t)(bit(RCONbits::POR) | bit(RCONbits::BOR) | bit(RCONbits::WDTO) |
                 bit(RCONbits::SWR) | bit(RCONbits::EXTR) | bit(RCONbits::TRAPR));
  RCON::modify(flags, 0);
  return (uint16_t)(cause & flags);
}

// Records the trap and resets: a controller that ran into a trap must not drive motors.
static void trap(uint8_t cause) {
  g_trap_cause = cause;
  g_trap_check = (uint8_t)(cause ^ 0xFFu);
#if DSPIC_TARGET
  __asm__ volatile("reset");
#endif
}

// Trap flags live in INTCON1 and must be cleared, or the trap repeats.
template <uint8_t kFlag>
inline void take_trap(uint8_t cause) {
  INTCON1::clear_bit<kFlag>();
  trap(cause);
}

}  // namespace dspic

namespace hal {

// Raises the CPU priority to 7 (masks every peripheral interrupt; traps still run).
// SR is saved and restored by every interrupt, so this read-modify-write cannot race.
uint16_t irq_save() {
  const uint16_t sr = dspic::SR::read();
  dspic::SR::write((uint16_t)(sr | dspic::kIplMask));
  return (uint16_t)(sr & dspic::kIplMask);
}

void irq_restore(uint16_t saved) {
  dspic::SR::modify(dspic::kIplMask, (uint16_t)(saved & dspic::kIplMask));
}

}  // namespace hal

DSPIC_ISR(_T1Interrupt) {
  dspic::timer1_acknowledge();
  if (dspic::g_tick != 0) dspic::g_tick(dspic::g_tick_context);
}

DSPIC_ISR(_U1RXInterrupt) {
  dspic::serve<dspic::Uart1, &dspic::Uart1::on_rx_interrupt, dspic::IFS0, dspic::IFS0bits::U1RXIF>(
      dspic::g_uart1);
}

DSPIC_ISR(_U1TXInterrupt) {
  dspic::serve<dspic::Uart1, &dspic::Uart1::on_tx_interrupt, dspic::IFS0, dspic::IFS0bits::U1TXIF>(
      dspic::g_uart1);
}

DSPIC_ISR(_INT1Interrupt) {
  dspic::serve<dspic::ProbePin, &dspic::ProbePin::on_int1_interrupt, dspic::IFS1,
               dspic::IFS1bits::INT1IF>(dspic::g_probe);
}

DSPIC_ISR(_OscillatorFail) {
  dspic::take_trap<dspic::INTCON1bits::OSCFAIL>(dspic::kTrapOscillatorFail);
}
DSPIC_ISR(_AddressError) {
  dspic::take_trap<dspic::INTCON1bits::ADDRERR>(dspic::kTrapAddressError);
}
DSPIC_ISR(_StackError) {
  dspic::take_trap<dspic::INTCON1bits::STKERR>(dspic::kTrapStackError);
}
DSPIC_ISR(_MathError) {
  dspic::take_trap<dspic::INTCON1bits::MATHERR>(dspic::kTrapMathError);
}
