// Planted violation: C++ standard headers (the first one is fatal for clang, so nothing
// after it is parsed; the token view still sees the second).
#include <new>  // expect: std-header
#include <stdint.h>  // allowed
#include <cstdint>  // expect: std-header
