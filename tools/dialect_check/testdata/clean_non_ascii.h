// A clean header whose comments hold multi-byte UTF-8 (µ, §, —, °) before its enums: clang's
// byte offsets must not be read as character positions (that once gave a false opaque-enum).
#ifndef TESTDATA_CLEAN_NON_ASCII_H
#define TESTDATA_CLEAN_NON_ASCII_H

#include <stdint.h>  // uint8_t, uint16_t

// Units: µm, µs, °C; see § 4.2 — “quoted” text. Each of these characters is 2 or 3 bytes:
// µµµµµµµµµµµµµµµµµµµµ §§§§§§§§§§§§§§§§§§§§ —————————————————————— °°°°°°°°°°°°°°°°°°°°
namespace clean_non_ascii {

enum class Mode : uint8_t { kIdle = 0, kRun = 1 };  // µ

// A one-line enum inside a class template, instantiated below (the instantiated copy carries
// a collapsed source range, so the check reads the source text after it).
template <uint16_t kAddress>
struct Sfr16 {
  enum { kWidth = 16 };  // bits — µ
  static uint16_t address() { return kAddress; }
};
typedef Sfr16<0x02C0> Trisd;
inline uint16_t width_of_trisd() {
  return Trisd::kWidth + Trisd::address();
}

// An enum written inside a macro body, used with a trailing ';' (spelled in the macro).
#define CLEAN_NON_ASCII_DECLARE(name) enum class name : uint8_t { kA = 0, kB = 1 }
CLEAN_NON_ASCII_DECLARE(Pair);

// A ';' inside a comment between the enum head and its brace.
enum class Dir : uint8_t  // plus; minus — µ
{
  kPlus = 0,
  kMinus = 1
};

}  // namespace clean_non_ascii

#endif  // TESTDATA_CLEAN_NON_ASCII_H
