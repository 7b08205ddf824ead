// TMC428 RAM tables: driver chain for three TMC246 and the micro-step sine table.
#include "hal/drivers/tmc428/tmc428_tables.h"  // declarations

#include "hal/drivers/tmc428/tmc428_regs.h"  // primary signal codes

namespace drivers {
namespace tmc428 {

// One TMC246 datagram, bit 11 first (TMC428 data sheet Tab. 11-2 layout). Mixed decay
// follows FD_x on all three drivers: on exactly while |sin| resp. |cos| falls (TMC428 data sheet
// Tab. 12-3), which is what the TMC246 wants ([246DS] §3.1). The last signal carries NxM.
#define TMC246_SIGNALS                                                                   \
  kSigFdA, kSigDacA0 + 5, kSigDacA0 + 4, kSigDacA0 + 3, kSigDacA0 + 2, kSigPhA, kSigFdB, \
      kSigDacB0 + 5, kSigDacB0 + 4, kSigDacB0 + 3, kSigDacB0 + 2, kSigPhB + kSigNxM

// Motors 1, 2, 3 (36 entries), then entries never reached with LSMD = 2, filled with the
// constant One as Trinamic's tmc428_base.c does (TMC428 RAM is random at power-on).
const uint8_t kDriverChainTable[kRamEntries] = {
    TMC246_SIGNALS, TMC246_SIGNALS, TMC246_SIGNALS, kSigOne, kSigOne, kSigOne, kSigOne, kSigOne,
    kSigOne,        kSigOne,        kSigOne,        kSigOne, kSigOne, kSigOne, kSigOne, kSigOne,
    kSigOne,        kSigOne,        kSigOne,        kSigOne, kSigOne, kSigOne, kSigOne, kSigOne,
    kSigOne,        kSigOne,        kSigOne,        kSigOne, kSigOne, kSigOne, kSigOne};

#undef TMC246_SIGNALS

// Generated from the formula above (docs/tmc428.md); matches the [429DS] §12 listing.
// host_tests/hal/tmc428 recomputes it in double precision.
const uint8_t kSineTable[kRamEntries] = {
    0x00, 0x02, 0x03, 0x05, 0x06, 0x08, 0x09, 0x0B, 0x0C, 0x0E, 0x10, 0x11, 0x13, 0x14, 0x16, 0x17,
    0x18, 0x1A, 0x1B, 0x1D, 0x1E, 0x20, 0x21, 0x22, 0x24, 0x25, 0x26, 0x27, 0x29, 0x2A, 0x2B, 0x2C,
    0x2D, 0x2E, 0x2F, 0x30, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37, 0x38, 0x38, 0x39, 0x3A, 0x3B,
    0x3B, 0x3C, 0x3C, 0x3D, 0x3D, 0x3E, 0x3E, 0x3E, 0x3F, 0x3F, 0x3F, 0x3F, 0x3F, 0x3F, 0x3F, 0x3F,
};

}  // namespace tmc428
}  // namespace drivers
