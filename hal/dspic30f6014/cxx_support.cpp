// The one C++ runtime hook the firmware needs on the target (XC16++ ships no libsupc++):
// abstract interfaces' vtables name __cxa_pure_virtual. Reaching it is a bug; reset.
#include "hal/dspic30f6014/platform.h"  // DSPIC_TARGET

#if DSPIC_TARGET
extern "C" void __cxa_pure_virtual() { __asm__ volatile("reset"); }
#endif
