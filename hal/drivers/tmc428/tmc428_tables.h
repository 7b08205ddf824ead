// The TMC428 on-chip RAM contents this board needs: the driver-chain configuration for
// three TMC246 and the quarter-sine micro-step table ([428DS] §10-12).
#ifndef HAL_DRIVERS_TMC428_TMC428_TABLES_H
#define HAL_DRIVERS_TMC428_TMC428_TABLES_H

#include <stdint.h>  // uint8_t

namespace drivers {
namespace tmc428 {

enum { kRamEntries = 64 };  // 6-bit entries per table (32 datagrams of two)

// Driver-chain RAM entries 0..63 (0x80..0xBE): per TMC246 the 12 signals MDA=FD_A,
// CA3..CA0=DAC_A 5..2, PHA, MDB=FD_B, CB3..CB0=DAC_B 5..2, PHB+NxM; unused entries = One.
extern const uint8_t kDriverChainTable[kRamEntries];

// Quarter sine y(i) = int(0.5 + 64 sin(i pi / 128)) clipped to 63, i = 0..63 ([428DS] §12).
extern const uint8_t kSineTable[kRamEntries];

}  // namespace tmc428
}  // namespace drivers

#endif  // HAL_DRIVERS_TMC428_TMC428_TABLES_H
