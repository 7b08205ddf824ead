// Integer square root (Crenshaw's bit-by-bit method): exact floor(sqrt(n)), no division.
#ifndef FIRMWARE_CORE_ISQRT_H
#define FIRMWARE_CORE_ISQRT_H

#include <stdint.h>  // uint32_t, uint16_t

namespace core {

// floor(sqrt(n)) for every 32-bit n (0..65535). 16 iterations of shift/compare/subtract.
uint16_t isqrt32(uint32_t n);

// The same floor(sqrt(n)), from a guess of it: when guess^2 is within n/256 of n (the guess
// within about 1/512 of the root) one Newton step (one short 32/16 division: DIV.UD on the
// dsPIC) and two or three products find it; otherwise isqrt32(n). Exact either way.
uint16_t isqrt32_from(uint32_t n, uint16_t guess);

}  // namespace core

#endif  // FIRMWARE_CORE_ISQRT_H
