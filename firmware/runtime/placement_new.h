// Placement new for portable code. The target has no <new>, and on the host <new> already
// defines operator new(size_t, void*) (noexcept), so redeclaring that one would clash; ours
// takes a tag argument instead:  T* t = new (storage, core::InPlace()) T(args);
#ifndef FIRMWARE_RUNTIME_PLACEMENT_NEW_H
#define FIRMWARE_RUNTIME_PLACEMENT_NEW_H

#include <stddef.h>  // size_t

namespace core {

// Tag selecting the placement operator new below.
struct InPlace {};

}  // namespace core

// Constructs in caller-provided storage (suitably sized and aligned); never allocates.
inline void* operator new(size_t, void* where, core::InPlace) {
  return where;
}

// Matching placement delete; only called if a constructor throws, which cannot happen here.
inline void operator delete(void*, void*, core::InPlace) {}

#endif  // FIRMWARE_RUNTIME_PLACEMENT_NEW_H
