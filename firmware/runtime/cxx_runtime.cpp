// The few C++ runtime hooks that GCC-generated code calls on a target with no C++ library
// (XC16++ on the dsPIC, avr-g++ on the proxy). Deliberately absent: operator new/delete,
// __cxa_atexit and the exception/RTTI support, so code needing them fails to link.
#include <stdint.h>  // uint8_t

// Where the runtime stops on a program error. Weak: the dsPIC port may override it (e.g. to
// cut the motor drivers and wait for the watchdog).
extern "C" void runtime_halt(void) __attribute__((weak, noreturn));

extern "C" void runtime_halt(void) {
  for (;;) {
  }
}

// Called from a vtable slot of a pure virtual function: only reachable through a bug (a call
// during construction/destruction of an abstract base).
extern "C" void __cxa_pure_virtual(void) {
  runtime_halt();
}

// Guards for function-local statics with a dynamic initialiser. The portable libraries are
// built with -fno-threadsafe-statics, so these are only a fallback; single core, no threads,
// so byte 0 of the guard (the Itanium ABI's "initialised" flag) is all the state needed.
extern "C" int __cxa_guard_acquire(uint8_t* guard) {
  return guard[0] == 0 ? 1 : 0;
}

extern "C" void __cxa_guard_release(uint8_t* guard) {
  guard[0] = 1;
}

extern "C" void __cxa_guard_abort(uint8_t*) {}
