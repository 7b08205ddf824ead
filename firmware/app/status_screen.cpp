// LCD status lines (see status_screen.h).
#include "firmware/app/status_screen.h"

#include <string.h>  // memcpy, memset, strcmp

namespace app {

namespace {

// A line being written: every character goes through put_char, which stops at kCols (one
// bound for text and numbers alike).
struct Line {
  char* out;
  uint8_t n;
};

void put_char(Line* l, char c) {
  if (l->n < StatusScreen::kCols) l->out[l->n++] = c;
}

void put(Line* l, const char* s) {
  while (*s) put_char(l, *s++);
}

void put_uint(Line* l, uint32_t v) {
  char digits[10];
  uint8_t k = 0;
  do {
    digits[k++] = (char)('0' + v % 10U);
    v /= 10U;
  } while (v != 0);
  while (k != 0) put_char(l, digits[--k]);
}

// "-12.34": millimetres with two decimals, rounded from micrometres.
void put_mm(Line* l, int32_t um) {
  uint32_t mag = (uint32_t)um;
  if (um < 0) {
    put_char(l, '-');
    mag = (uint32_t)0 - (uint32_t)um;
  }
  const uint32_t hundredths = (mag + 5U) / 10U;
  put_uint(l, hundredths / 100U);
  put_char(l, '.');
  const uint8_t cents = (uint8_t)(hundredths % 100U);
  put_char(l, (char)('0' + cents / 10U));
  put_char(l, (char)('0' + cents % 10U));
}

void end_line(Line* l) {
  l->out[l->n] = 0;
}

// By proto::MachineState (kIdle shows READY once zeroed).
const char* const kStateNames[] = {"IDLE", "RUN", "HOLDING", "HOLD", "ZEROING", "ALARM", "PAUSED"};

const char* state_name(proto::MachineState s, bool zeroed) {
  if (s == proto::MachineState::kIdle && zeroed) return "READY";
  const uint8_t i = (uint8_t)s;
  return i < sizeof kStateNames / sizeof kStateNames[0] ? kStateNames[i] : "?";
}

// By proto::Alarm, from kLimitSwitch (1) to kLastAlarm.
const char* const kAlarmNames[proto::kLastAlarm] = {
    "LIMIT SWITCH", "DRIVER FAULT",   "POWER LOST",    "FOLLOWING ERR",
    "MOTION CHIP",  "PATH FAULT",     "SOFT LIMIT",    "PROBE NO TOUCH",
    "PROBE CLOSED", "PROBE: SPINDLE", "NO PROBE INPUT"};

const char* alarm_name(proto::Alarm a) {
  const uint8_t i = (uint8_t)a;
  return i >= 1 && i <= proto::kLastAlarm ? kAlarmNames[i - 1] : "ALARM";
}

}  // namespace

// Every member starts at zero (empty texts): one memset, less code than a store each (no
// virtuals).
StatusScreen::StatusScreen() {
  memset(static_cast<void*>(this), 0, sizeof *this);
}

void StatusScreen::init(hal::TextDisplay* display) {
  display_ = display;
  drawn_once_ = false;
}

void StatusScreen::show_text(uint8_t row, const char* text, uint8_t length, uint16_t now_ms) {
  if (row > 1) return;
  if (length > kCols) length = kCols;
  memcpy(text_[row], text, length);
  text_[row][length] = 0;
  text_on_[row] = true;
  text_ms_[row] = now_ms;
}

void StatusScreen::show_pause(const char* text, uint8_t length) {
  if (length > kCols) length = kCols;
  memcpy(pause_, text, length);
  pause_[length] = 0;
}

void StatusScreen::show_error(proto::ErrorCode code, uint8_t seq, uint16_t now_ms) {
  Line l = {error_, 0};
  put(&l, "ERR ");
  put_uint(&l, (uint8_t)code);
  put(&l, " #");
  put_uint(&l, seq);
  end_line(&l);
  error_on_ = true;
  error_ms_ = now_ms;
}

void StatusScreen::compose(const ScreenInfo& info, uint16_t now_ms, char out[2][kCols + 1]) {
  for (uint8_t r = 0; r < 2; ++r) {
    if (text_on_[r] && (uint16_t)(now_ms - text_ms_[r]) >= (uint16_t)kMessageMs)
      text_on_[r] = false;
  }
  if (error_on_ && (uint16_t)(now_ms - error_ms_) >= (uint16_t)kMessageMs) error_on_ = false;
  Line l = {out[0], 0};
  if (info.paused) {
    put(&l, pause_[0] != 0 ? pause_ : "PAUSED");
  } else if (text_on_[0]) {
    put(&l, text_[0]);
  } else {
    put(&l, state_name(info.state, info.zeroed));
    if (info.state == proto::MachineState::kZeroing) {
      put(&l, info.z_mode ? " Z" : " XY");
    } else if (info.items_stored != 0) {
      put_char(&l, ' ');
      put_uint(&l, info.items_done);
      put_char(&l, '/');
      put_uint(&l, info.items_stored);
    }
  }
  end_line(&l);
  l.out = out[1];
  l.n = 0;
  if (info.state == proto::MachineState::kAlarm) {
    put(&l, alarm_name(info.alarm));
  } else if (error_on_) {
    put(&l, error_);
  } else if (info.paused) {
    put(&l, "CONFIRM TO GO ON");
  } else if (text_on_[1]) {
    put(&l, text_[1]);
  } else if (info.probing || info.probe_closed) {
    // "PROBE Z-0.14" while a #Y runs; "PROBE TOUCH Z.." whenever the input reads closed
    // (the operator sees the clip work before probing, or that it is shorted).
    put(&l, info.probe_closed ? "PROBE TOUCH Z" : "PROBE Z");
    put_mm(&l, info.pos_um[2]);
  } else {
    // "X12.34 Y-5.60" (Z while zeroing Z).
    const bool z = info.state == proto::MachineState::kZeroing && info.z_mode;
    put(&l, z ? "Z" : "X");
    put_mm(&l, z ? info.pos_um[2] : info.pos_um[0]);
    if (!z) {
      put(&l, " Y");
      put_mm(&l, info.pos_um[1]);
    }
  }
  end_line(&l);
}

void StatusScreen::update(const ScreenInfo& info, uint16_t now_ms) {
  if (display_ == 0) return;
  if (drawn_once_ && (uint16_t)(now_ms - last_draw_ms_) < (uint16_t)kRefreshMs) return;
  last_draw_ms_ = now_ms;
  char next[2][kCols + 1];
  compose(info, now_ms, next);
  for (uint8_t r = 0; r < 2; ++r) {
    if (drawn_once_ && strcmp(next[r], shown_[r]) == 0) continue;
    memcpy(shown_[r], next[r], kCols + 1);
    display_->write_line(r, shown_[r]);
  }
  drawn_once_ = true;
}

}  // namespace app
