// The LCD's state and alarm names, one per wire code (the names come from tables indexed
// by the code: an entry out of place shows another alarm's name); the numbers on the lines
// (position, progress, error, probe), rounded and cut at 16 columns.
#include <gtest/gtest.h>

#include <string>

#include "firmware/app/status_screen.h"

namespace {

class LineDisplay : public hal::TextDisplay {
 public:
  void write_line(uint8_t row, const char* text) override { rows[row] = text; }
  void clear() override {}
  std::string rows[2];
};

app::ScreenInfo idle_info() {
  app::ScreenInfo info = {};
  info.state = proto::MachineState::kIdle;
  info.alarm = proto::Alarm::kNone;
  return info;
}

// The two lines shown for info, drawn afresh.
std::string line(const app::ScreenInfo& info, int row) {
  LineDisplay display;
  app::StatusScreen screen;
  screen.init(&display);
  screen.update(info, 0);
  return display.rows[row];
}

TEST(StatusScreen, EveryStateHasItsName) {
  const char* const names[] = {"IDLE", "RUN", "HOLDING", "HOLD", "ZEROING XY", "ALARM", "PAUSED"};
  for (uint8_t s = 0; s < 7; ++s) {
    app::ScreenInfo info = idle_info();
    info.state = (proto::MachineState)s;
    EXPECT_EQ(line(info, 0), names[s]) << "state " << int(s);
  }
  app::ScreenInfo ready = idle_info();
  ready.zeroed = true;
  EXPECT_EQ(line(ready, 0), "READY");
  app::ScreenInfo unknown = idle_info();
  unknown.state = (proto::MachineState)7;
  EXPECT_EQ(line(unknown, 0), "?");
}

TEST(StatusScreen, EveryAlarmHasItsName) {
  const char* const names[] = {"LIMIT SWITCH", "DRIVER FAULT",   "POWER LOST",    "FOLLOWING ERR",
                               "MOTION CHIP",  "PATH FAULT",     "SOFT LIMIT",    "PROBE NO TOUCH",
                               "PROBE CLOSED", "PROBE: SPINDLE", "NO PROBE INPUT"};
  for (uint8_t a = 1; a <= proto::kLastAlarm; ++a) {
    app::ScreenInfo info = idle_info();
    info.state = proto::MachineState::kAlarm;
    info.alarm = (proto::Alarm)a;
    EXPECT_EQ(line(info, 1), names[a - 1]) << "alarm " << int(a);
  }
  app::ScreenInfo none = idle_info();
  none.state = proto::MachineState::kAlarm;
  EXPECT_EQ(line(none, 1), "ALARM");
  none.alarm = (proto::Alarm)(proto::kLastAlarm + 1);
  EXPECT_EQ(line(none, 1), "ALARM");
}

TEST(StatusScreen, PositionInMillimetresRoundedToHundredths) {
  app::ScreenInfo info = idle_info();
  info.pos_um[0] = 12345;  // 12.345 rounds up
  info.pos_um[1] = -5604;  // -5.604 rounds down in magnitude
  EXPECT_EQ(line(info, 1), "X12.35 Y-5.60");
  info.pos_um[0] = 4;
  info.pos_um[1] = -995;
  EXPECT_EQ(line(info, 1), "X0.00 Y-1.00");
  info.pos_um[0] = 2147483647;  // cut at 16 columns
  info.pos_um[1] = 0;
  EXPECT_EQ(line(info, 1), "X2147483.65 Y0.0");
  info.pos_um[0] = -2147483647 - 1;
  EXPECT_EQ(line(info, 1), "X-2147483.65 Y0.");
  info.state = proto::MachineState::kZeroing;
  info.z_mode = true;
  info.pos_um[2] = -70;
  EXPECT_EQ(line(info, 0), "ZEROING Z");
  EXPECT_EQ(line(info, 1), "Z-0.07");
}

TEST(StatusScreen, ProgressAndProbeLines) {
  app::ScreenInfo info = idle_info();
  info.state = proto::MachineState::kRunning;
  info.items_done = 7;
  info.items_stored = 120;
  EXPECT_EQ(line(info, 0), "RUN 7/120");
  info.state = proto::MachineState::kHolding;
  info.items_done = 65535;
  info.items_stored = 65535;
  EXPECT_EQ(line(info, 0), "HOLDING 65535/65");
  info.probing = true;
  info.pos_um[2] = -140;
  EXPECT_EQ(line(info, 1), "PROBE Z-0.14");
  info.probe_closed = true;
  EXPECT_EQ(line(info, 1), "PROBE TOUCH Z-0.");
}

TEST(StatusScreen, ErrorLineShowsCodeAndSeq) {
  LineDisplay display;
  app::StatusScreen screen;
  screen.init(&display);
  screen.show_error((proto::ErrorCode)42, 255, 0);
  screen.update(idle_info(), 0);
  EXPECT_EQ(display.rows[1], "ERR 42 #255");
  screen.show_error((proto::ErrorCode)0, 0, 200);
  screen.update(idle_info(), 200);
  EXPECT_EQ(display.rows[1], "ERR 0 #0");
}

}  // namespace
