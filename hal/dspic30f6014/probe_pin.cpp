// Probe input on RA12 / INT1 (pin map in pins.h, priorities in interrupts.h).
#include "hal/dspic30f6014/probe_pin.h"

#include "hal/dspic30f6014/interrupts.h"  // kProbePriority
#include "hal/dspic30f6014/pins.h"        // kProbeBit
#include "hal/dspic30f6014/registers.h"   // TRISA, PORTA, INTCON2, IFS1, IEC1, IPC4

namespace dspic {

void ProbePin::init() {
  TRISA::set_bit<pins::kProbeBit>();  // input (also the reset state)
  INTCON2::set_bit<INTCON2bits::INT1EP>();
  IPC4::modify((uint16_t)(7U << IPC4bits::INT1IP), (uint16_t)(kProbePriority << IPC4bits::INT1IP));
  IFS1::clear_bit<IFS1bits::INT1IF>();
  touched_ = false;
  IEC1::set_bit<IEC1bits::INT1IE>();
}

bool ProbePin::closed() {
  const bool low = (PORTA::read() & bit(pins::kProbeBit)) == 0;
  const bool touched = touched_;  // INT1 runs below the tick: it cannot change it meanwhile
  touched_ = false;
  return low || touched;
}

void ProbePin::on_int1_interrupt() {
  IFS1::clear_bit<IFS1bits::INT1IF>();
  touched_ = true;
}

}  // namespace dspic
