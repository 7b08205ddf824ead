// The LCD's state and alarm names, one per wire code (the names come from tables indexed
// by the code: an entry out of place shows another alarm's name).
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

}  // namespace
