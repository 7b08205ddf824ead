// The two LCD lines: state and job progress (or a pause's text) on top, then (by priority)
// the alarm, the last error, the pause prompt, text sent with #S, or the position. Redrawn only
// when a line changes, at most every kRefreshMs, from the background loop.
#ifndef FIRMWARE_APP_STATUS_SCREEN_H
#define FIRMWARE_APP_STATUS_SCREEN_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/protocol/wire_codes.h"  // MachineState, Alarm, ErrorCode
#include "hal/interfaces/text_display.h"   // TextDisplay

namespace app {

struct ScreenInfo {
  proto::MachineState state;
  proto::Alarm alarm;
  bool zeroed;
  bool z_mode;          // zeroing: joystick drives Z
  bool paused;          // a #P waits: its text on top, the confirm prompt below
  bool probing;         // a #Y descends or retracts: "PROBE Z..." below
  bool probe_closed;    // the probe input reads closed (debounced)
  uint16_t items_done;  // job progress since the session started
  uint16_t items_stored;
  int32_t pos_um[3];
};

class StatusScreen {
 public:
  enum { kCols = 16, kRefreshMs = 100, kMessageMs = 3000 };
  StatusScreen();
  void init(hal::TextDisplay* display);
  // #S text for a row (shown for kMessageMs, row 0 then replaces the state line).
  void show_text(uint8_t row, const char* text, uint8_t length, uint16_t now_ms);
  // #P text, shown on row 0 while ScreenInfo::paused (an empty text shows "PAUSED").
  void show_pause(const char* text, uint8_t length);
  // A rejected frame: "ERR <code> #<seq>" for kMessageMs.
  void show_error(proto::ErrorCode code, uint8_t seq, uint16_t now_ms);
  void update(const ScreenInfo& info, uint16_t now_ms);
  // What the display shows (for tests and the simulator).
  const char* line(uint8_t row) const { return shown_[row]; }

 private:
  void compose(const ScreenInfo& info, uint16_t now_ms, char out[2][kCols + 1]);

  hal::TextDisplay* display_;
  uint16_t last_draw_ms_;
  uint16_t text_ms_[2];
  uint16_t error_ms_;
  bool text_on_[2];
  bool error_on_;
  bool drawn_once_;
  char text_[2][kCols + 1];
  char error_[kCols + 1];
  char pause_[kCols + 1];
  char shown_[2][kCols + 1];
};

}  // namespace app

#endif  // FIRMWARE_APP_STATUS_SCREEN_H
