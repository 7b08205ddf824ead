// Integer square root (Crenshaw's bit-by-bit method): exact floor(sqrt(n)), no division.
#ifndef FIRMWARE_CORE_ISQRT_H
#define FIRMWARE_CORE_ISQRT_H

#include <stdint.h>  // uint32_t, uint16_t

namespace core {

// floor(sqrt(n)) for every 32-bit n (0..65535). 16 iterations of shift/compare/subtract.
uint16_t isqrt32(uint32_t n);

}  // namespace core

#endif  // FIRMWARE_CORE_ISQRT_H
