/* Configuration words for the dsPIC30F6014 on this board (data sheet DS70117, config bits):
   10 MHz crystal, XT with PLL x8 (Fcy 20 MHz), no fail-safe clock switch, watchdog off,
   64 ms power-up timer, brown-out reset off, MCLR enabled, no code protection.
   C (not C++): the device header's config macros need the C compiler. */
#include <p30fxxxx.h>

// The formatter reads `A & B` in a macro argument as a reference type.
// clang-format off
_FOSC(CSW_FSCM_OFF & XT_PLL8);
_FWDT(WDT_OFF);
_FBORPOR(PWRT_64 & PBOR_OFF & MCLR_EN);
_FGS(CODE_PROT_OFF);
// clang-format on
