// Deliberately NOT clang-formatted: format_check must reject this file (test_format_check.py).
#include <stdint.h>  // uint16_t

namespace demo {
uint16_t  twice( uint16_t x ){return x*2;}
}  // namespace demo
