// The operator's status screen on a 16x2 text display: machine state and Z on row 0,
// X and Y on row 1, positions in mm with two decimals ("RUN      Z -1.25" / "X 12.50  Y210.00").
#ifndef HAL_DRIVERS_HD44780_STATUS_SCREEN_H
#define HAL_DRIVERS_HD44780_STATUS_SCREEN_H

#include <stdint.h>  // int32_t

#include "firmware/config/machine_config.h"  // config::kAxisCount
#include "hal/interfaces/text_display.h"     // hal::TextDisplay

namespace drivers {

struct StatusView {
  const char* state;                        // short state name; first 8 characters shown
  int32_t position_um[config::kAxisCount];  // X, Y, Z
};

enum {
  kStatusRowChars = 16,  // hal::TextDisplay::kColumns
  kMmFieldChars = 6      // "-99.99" .. "999.99"
};

// Position in um as mm, rounded to 0.01 mm, right-aligned in kMmFieldChars characters
// (no NUL); "######" when outside -99.99 .. 999.99 mm.
void format_mm(int32_t position_um, char out[kMmFieldChars]);
// Both rows, each kStatusRowChars characters plus a NUL.
void format_status(const StatusView& view, char row0[kStatusRowChars + 1],
                   char row1[kStatusRowChars + 1]);
// Formats and writes both rows.
void show_status(hal::TextDisplay* display, const StatusView& view);

}  // namespace drivers

#endif  // HAL_DRIVERS_HD44780_STATUS_SCREEN_H
