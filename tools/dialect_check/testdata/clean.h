// A clean header: every construct the target dialect accepts. Comments and strings may
// mention constexpr, nullptr, std::vector, [[noreturn]] and #include <new> freely.
#ifndef TESTDATA_CLEAN_H
#define TESTDATA_CLEAN_H

#include <stddef.h>  // size_t
#include <stdint.h>  // int32_t, uint16_t
#include <string.h>  // memcpy
#include <limits.h>  // INT_MAX

// Placement new with an operator we declare ourselves (there is no <new>).
inline void* operator new(size_t, void* where) { return where; }

namespace clean {

enum class Axis : uint8_t { kX = 0, kY = 1, kZ = 2 };

typedef int32_t Micrometres;

// An interface with a protected non-virtual destructor.
class Sink {
 public:
  virtual void put(uint8_t byte) = 0;

 protected:
  ~Sink() {}
};

template <typename T, uint16_t kCapacity>
struct Fixed {
  T items[kCapacity];
  uint16_t used;
  Fixed() : used(0) {}
};

inline int32_t sum() { return 0; }

// A variadic template.
template <typename... Rest>
int32_t sum(int32_t first, Rest... rest) {
  return first + sum(rest...);
}

struct Pair {
  int32_t a;
  int32_t b;
};

static_assert(sizeof(Pair) == 8, "two 32-bit fields");

}  // namespace clean

#endif
