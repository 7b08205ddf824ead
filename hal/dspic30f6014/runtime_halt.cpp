// Where the C++ runtime (firmware/runtime: __cxa_pure_virtual) stops on a program error:
// on the dsPIC a software reset, so the motors lose their drive and the start-up screen
// shows the restart. Replaces the weak endless loop in firmware/runtime/cxx_runtime.cpp.
#include "hal/dspic30f6014/platform.h"  // DSPIC_TARGET

#if DSPIC_TARGET
extern "C" void runtime_halt(void) __attribute__((noreturn));

extern "C" void runtime_halt(void) {
  __asm__ volatile("reset");
  for (;;) {
  }
}
#endif
