// Timer1 as the 1 ms tick: Fcy clock, 1:1 prescale, PR1 = Fcy / 1000 - 1 = 19999.
#ifndef HAL_DSPIC30F6014_TIMER1_H
#define HAL_DSPIC30F6014_TIMER1_H

#include <stdint.h>  // uint16_t

namespace dspic {

enum { kTickHz = 1000 };

// PR1 for the tick at the board's Fcy (19999 at 20 MHz with 1:1 prescale).
uint16_t timer1_period_for_tick();
// Starts Timer1 with its interrupt enabled (priority from configure_interrupt_priorities()).
void timer1_start_1ms();
// Acknowledges the tick interrupt (clears T1IF); the vector calls it first.
void timer1_acknowledge();

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_TIMER1_H
