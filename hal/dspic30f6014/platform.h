// Tells the real dsPIC build (XC16/XC16++) from the host build of the port, and hides the
// target-only attributes (interrupt vectors, persistent RAM) behind macros.
#ifndef HAL_DSPIC30F6014_PLATFORM_H
#define HAL_DSPIC30F6014_PLATFORM_H

#if defined(__XC16__) || defined(__C30__)
#define DSPIC_TARGET 1
#else
#define DSPIC_TARGET 0
#endif

#if DSPIC_TARGET
// An interrupt vector: XC16 saves the context, returns with RETFIE and places the function
// in the IVT slot its name selects (XC16 p30F6014A.gld vector table). no_auto_psv: the ISRs
// read no const data through the PSV window, so PSVPAG need not be saved.
#define DSPIC_ISR(name) extern "C" void __attribute__((interrupt, no_auto_psv)) name(void)
// Not cleared by the C start-up code, so a trap handler can leave a note across a reset.
#define DSPIC_PERSISTENT __attribute__((persistent))
#else
// On the host a vector is an ordinary function the tests call.
#define DSPIC_ISR(name) extern "C" void name(void)
#define DSPIC_PERSISTENT
#endif

#endif  // HAL_DSPIC30F6014_PLATFORM_H
