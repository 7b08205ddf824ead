// Planted violations after multi-byte UTF-8 text: each must be reported on its own line.
// µµµµµµµµµµµµµµµµµµµµµµµµµµµµµµ §§§§§§§§§§§§§§§§§§§§§§§§§§§§§§ ——————————————————————————————
#include <stdint.h>  // uint8_t

enum class Opaque : uint8_t;  // expect: opaque-enum
struct After {
  int value;
};

// “Quoted” text — and more µ before a nullptr.
int* pick_after_utf8(int* p) {
  return p == nullptr ? 0 : p;  // expect: nullptr
}
