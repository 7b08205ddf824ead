// Timer1 1 ms tick (dsPIC30F Family Reference Manual, Timers sec. 12.5-12.6).
#include "hal/dspic30f6014/timer1.h"

#include "hal/dspic30f6014/clock.h"      // kFcyHz
#include "hal/dspic30f6014/registers.h"  // T1CON, TMR1, PR1, IFS0, IEC0

namespace dspic {

// Period = (PR1 + 1) * prescale / Fcy; with 1:1, PR1 + 1 = Fcy / 1000 = 20000 fits 16 bits.
uint16_t timer1_period_for_tick() {
  return (uint16_t)(kFcyHz / kTickHz - 1u);
}

// TCS = 0 (Fcy), TCKPS = 00 (1:1), TGATE = 0; the interrupt needs T1IE and T1IP != 0.
void timer1_start_1ms() {
  T1CON::write(0);
  TMR1::write(0);
  PR1::write(timer1_period_for_tick());
  IFS0::clear_bit<IFS0bits::T1IF>();
  IEC0::set_bit<IEC0bits::T1IE>();
  T1CON::write(bit(T1CONbits::TON));
}

void timer1_acknowledge() {
  IFS0::clear_bit<IFS0bits::T1IF>();
}

}  // namespace dspic
